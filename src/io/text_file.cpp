#include "adjoin/io/text_file.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "adjoin/errors.hpp"

namespace adjoin {
namespace {

// Length of the valid UTF-8 sequence starting at s[i] (1 to 4), or 0 if it is not one.
std::size_t utf8_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned int min = 0, code = 0;
  if ((c & 0xE0) == 0xC0) { n = 2; code = c & 0x1F; min = 0x80; }
  else if ((c & 0xF0) == 0xE0) { n = 3; code = c & 0x0F; min = 0x800; }
  else if ((c & 0xF8) == 0xF0) { n = 4; code = c & 0x07; min = 0x10000; }
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  // Overlong forms, surrogates and code points beyond Unicode are not UTF-8.
  if (code < min || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return n;
}

std::string hex_byte(unsigned char c) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "\\x%02X", c);
  return buffer;
}

std::size_t line_of(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) line += text[i] == '\n';
  return line;
}

std::string_view line_around(std::string_view text, std::size_t offset) {
  const std::size_t begin = text.rfind('\n', offset == 0 ? 0 : offset - 1);
  const std::size_t start = begin == std::string_view::npos || offset == 0 ? 0 : begin + 1;
  const std::size_t end = text.find('\n', offset);
  return text.substr(start, (end == std::string_view::npos ? text.size() : end) - start);
}

}  // namespace

std::string escaped_excerpt(std::string_view text, std::size_t max_chars) {
  std::string out;
  std::size_t chars = 0, i = 0;
  while (i < text.size() && chars < max_chars) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
    if (n == 0 || c < 0x20 || c == 0x7F) {
      out += c == '\n' ? std::string("\\n") : c == '\t' ? std::string("\\t") : hex_byte(c);
      i += 1;
    } else if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
      i += 1;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
    ++chars;
  }
  if (i < text.size()) out += "...";
  return "\"" + out + "\"";
}

std::string text_excerpt(std::string_view text) {
  const bool plain = text.size() <= 80 && text.find_first_of("\n\t") == std::string_view::npos &&
                     printable_message(text) == text;
  return plain ? std::string(text) : escaped_excerpt(text, 60);
}

std::string printable_message(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (std::size_t i = 0; i < message.size();) {
    const unsigned char c = static_cast<unsigned char>(message[i]);
    const std::size_t n = utf8_length(message, i);
    if (c == '\n' || c == '\t' || (n > 0 && c >= 0x20 && c != 0x7F)) {
      const std::size_t take = n > 0 ? n : 1;
      out.append(message.substr(i, take));
      i += take;
    } else {
      out += hex_byte(c);
      i += 1;
    }
  }
  return out;
}

std::string read_text_file(const std::filesystem::path& file, const std::string& what, std::size_t max_bytes) {
  const std::string name = file.string();
  struct stat info {};
  if (::stat(file.c_str(), &info) != 0) {
    const int error = errno;
    throw InputError(name + ": cannot open the " + what + " file: " + std::strerror(error));
  }
  if (S_ISDIR(info.st_mode))
    throw InputError(name + ": is a folder; expected a " + what + " file (TOML text)");
  if (!S_ISREG(info.st_mode))
    throw InputError(name + ": is not a regular file (a FIFO, device or socket); expected a " + what +
                     " file (TOML text) on disk");
  if (static_cast<std::size_t>(info.st_size) > max_bytes) {
    std::ostringstream s;
    s << name << ": is " << info.st_size << " bytes; a " << what << " file is text of at most " << max_bytes
      << " bytes (is this the right file?)";
    throw InputError(s.str());
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open the " + what + " file (permissions?)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();

  const auto starts = [&](std::string_view prefix) { return std::string_view(text).substr(0, prefix.size()) == prefix; };
  if (starts(std::string_view("\x00\x00\xFE\xFF", 4)) || starts(std::string_view("\xFF\xFE\x00\x00", 4)))
    throw InputError(name + ": is UTF-32 text; save the " + what + " file as UTF-8");
  if (starts("\xFE\xFF") || starts("\xFF\xFE"))
    throw InputError(name + ": is UTF-16 text; save the " + what + " file as UTF-8");
  if (starts("\xEF\xBB\xBF")) text.erase(0, 3);  // UTF-8 byte-order mark

  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
    const bool control = c < 0x20 && c != '\n' && c != '\t' && c != '\r';
    if (n == 0 || control) {
      std::ostringstream s;
      s << name << ":" << line_of(text, i) << ": ";
      if (c == 0)
        s << "holds a NUL byte; ";
      else if (n == 0)
        s << "holds bytes that are not UTF-8 text; ";
      else
        s << "holds a control character; ";
      s << "expected a " << what << " file (TOML text), got " << escaped_excerpt(line_around(text, i));
      throw InputError(s.str());
    }
    i += n;
  }
  return text;
}

std::string number_text(double v, int significant) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

}  // namespace adjoin
