// Empty: the owner of a precompiled header for the tests (test/test_build.cmake).
