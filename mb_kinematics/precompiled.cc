// The owner of the libraries' precompiled header (CMakeLists.txt, MBK_LIBRARY_HEADERS): a file
// with no code of its own, compiled with the header.
