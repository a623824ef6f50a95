#include "mb_kinematics/io/text_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "mb_kinematics/core/printable.h"

namespace mbk {
namespace {

// Closes the file however the reading ends.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

std::invalid_argument too_long(const std::string& source, const std::string& what,
                               std::size_t most) {
  return std::invalid_argument(printable(source) + ": " + what + " of more than " +
                               std::to_string(most) + " bytes, more than it can hold");
}

// The file opened for reading (its descriptor), once it is known to be a regular file (st: its
// status).
int open_regular(const std::string& path, const std::string& what, struct stat& st) {
  if (path.find('\0') != std::string::npos)
    throw std::invalid_argument(printable(path) + ": cannot open " + what +
                                ": the name holds a NUL byte");
  // O_NONBLOCK: a pipe is refused below, not waited on for a writer.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (file.fd < 0) throw std::invalid_argument(printable(path) + ": cannot open " + what);
  if (::fstat(file.fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw std::invalid_argument(printable(path) + ": cannot read " + what +
                                ": not a regular file (a device, a pipe or a folder)");
  return std::exchange(file.fd, -1);
}

}  // namespace

std::string read_text_stream(std::istream& in) {
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string read_text_stream(std::istream& in, const std::string& source, std::size_t most) {
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > most) throw too_long(source, "a text", most);
  }
  return text;
}

std::string read_text_file(const std::string& path, const std::string& what, std::size_t most) {
  struct stat st;
  const Descriptor file{open_regular(path, what, st)};
  if (static_cast<std::size_t>(st.st_size) > most) throw too_long(path, what, most);
  std::string text;
  text.reserve(static_cast<size_t>(st.st_size));
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<size_t>(n));
      if (text.size() > most) throw too_long(path, what, most);  // it grew while read
    } else if (n == 0) {
      return text;
    } else if (errno != EINTR) {
      throw std::invalid_argument(printable(path) + ": cannot read " + what);
    }
  }
}

void check_regular_file(const std::string& path, const std::string& what) {
  struct stat st;
  const Descriptor file{open_regular(path, what, st)};
}

bool xml_root_is(const std::string& xml, const std::string& element) {
  std::size_t at = 0;
  while (true) {  // skip the XML declaration, comments and blanks before the first element
    at = xml.find('<', at);
    if (at == std::string::npos) return false;
    if (xml.compare(at, 4, "<!--") == 0) {
      at = xml.find("-->", at);
      if (at == std::string::npos) return false;
    } else if (xml.compare(at, 2, "<?") != 0 && xml.compare(at, 2, "<!") != 0) {
      break;
    }
    ++at;
  }
  const std::string open = "<" + element;
  if (xml.compare(at, open.size(), open) != 0) return false;
  const char next = at + open.size() < xml.size() ? xml[at + open.size()] : '\0';
  return next == '>' || next == '/' || next == ' ' || next == '\t' || next == '\n' || next == '\r';
}

}  // namespace mbk
