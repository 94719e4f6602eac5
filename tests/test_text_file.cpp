// io/text_file: reading user text files and quoting bytes in messages.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/text_file.hpp"

using adjoin::escaped_excerpt;
using adjoin::InputError;
using adjoin::printable_message;
using adjoin::read_text_file;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path write(const std::string& name, const std::string& bytes) {
  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "text_file";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("escaped_excerpt: control bytes, invalid UTF-8, quotes, length", "[text_file]") {
  CHECK(escaped_excerpt(std::string("a\0b", 3)) == "\"a\\x00b\"");
  CHECK(escaped_excerpt("tab\there\n") == "\"tab\\there\\n\"");
  CHECK(escaped_excerpt("say \"hi\" \\ ok") == "\"say \\\"hi\\\" \\\\ ok\"");
  CHECK(escaped_excerpt("\x7f\xff\xfe") == "\"\\x7F\\xFF\\xFE\"");
  CHECK(escaped_excerpt("caf\xC3\xA9") == "\"caf\xC3\xA9\"");         // valid UTF-8 kept
  CHECK(escaped_excerpt("\xC0\x80") == "\"\\xC0\\x80\"");              // overlong NUL is not UTF-8
  CHECK(escaped_excerpt("\xED\xA0\x80") == "\"\\xED\\xA0\\x80\"");     // a surrogate is not UTF-8
  CHECK(escaped_excerpt("\xE2\x82") == "\"\\xE2\\x82\"");              // truncated sequence
  CHECK(escaped_excerpt(std::string(100, 'x'), 10) == "\"" + std::string(10, 'x') + "...\"");
  CHECK(escaped_excerpt("abc", 3) == "\"abc\"");
}

TEST_CASE("text_excerpt: short printable text as written, anything else as a short escaped excerpt", "[text_file]") {
  CHECK(adjoin::text_excerpt("solver.h=0.01") == "solver.h=0.01");
  CHECK(adjoin::text_excerpt("name=\"a b\"") == "name=\"a b\"");  // quotes as written
  CHECK(adjoin::text_excerpt(std::string(80, 'k')) == std::string(80, 'k'));
  const std::string long_key = adjoin::text_excerpt(std::string(100000, 'k'));
  CHECK(long_key == "\"" + std::string(60, 'k') + "...\"");
  CHECK(adjoin::text_excerpt("a\nb") == "\"a\\nb\"");
  CHECK(adjoin::text_excerpt(std::string("a\x01" "b", 3)) == "\"a\\x01b\"");
}

TEST_CASE("printable_message keeps text and newlines, escapes the rest", "[text_file]") {
  CHECK(printable_message("line 1\nline 2\tend") == "line 1\nline 2\tend");
  CHECK(printable_message(std::string("cut\0off", 7)) == "cut\\x00off");
  CHECK(printable_message("\x1b[31mred") == "\\x1B[31mred");
  CHECK(printable_message("\xff ok \xC3\xA9") == "\\xFF ok \xC3\xA9");
}

TEST_CASE("read_text_file: text in, everything else refused with file and line", "[text_file]") {
  CHECK(read_text_file(write("ok.toml", "a = 1\n# caf\xC3\xA9\n"), "scene") == "a = 1\n# caf\xC3\xA9\n");
  CHECK(read_text_file(write("bom.toml", "\xEF\xBB\xBF" "a = 1\n"), "scene") == "a = 1\n");
  CHECK(read_text_file(write("crlf.toml", "a = 1\r\nb = 2\r\n"), "scene") == "a = 1\r\nb = 2\r\n");

  const auto nul = write("nul.toml", std::string("a = 1\nb = 2\0\n", 13));
  CHECK_THROWS_WITH(read_text_file(nul, "scene"), Contains(nul.string() + ":2: holds a NUL byte") && Contains("\"b = 2\\x00\""));
  const auto bad = write("bad.toml", "a = 1\nb = 2\nc = \xFF\xFE\n");
  CHECK_THROWS_WITH(read_text_file(bad, "sweep"), Contains(bad.string() + ":3: holds bytes that are not UTF-8 text") &&
                                                      Contains("expected a sweep file") && Contains("\\xFF\\xFE"));
  CHECK_THROWS_WITH(read_text_file(write("u16.toml", std::string("\xFF\xFE" "a\0", 4)), "scene"), Contains("is UTF-16 text"));
  CHECK_THROWS_WITH(read_text_file(write("u32.toml", std::string("\xFF\xFE\0\0a\0\0\0", 8)), "scene"), Contains("is UTF-32 text"));
  CHECK_THROWS_WITH(read_text_file(write("esc.toml", "a = 1\x1b\n"), "scene"), Contains(":1: holds a control character"));

  const auto dir = std::filesystem::path(ADJOIN_TEST_TMP) / "text_file";
  CHECK_THROWS_WITH(read_text_file(dir, "scene"), Contains("is a folder"));
  CHECK_THROWS_WITH(read_text_file(dir / "missing.toml", "scene"), Contains("cannot open the scene file"));
  const auto fifo = dir / "fifo";
  std::filesystem::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(read_text_file(fifo, "scene"), Contains("is not a regular file"));  // and does not block

  const auto big = write("big.toml", "a = 1\n");
  std::filesystem::resize_file(big, 2000);
  CHECK_THROWS_WITH(read_text_file(big, "scene", 1000), Contains("is 2000 bytes; a scene file is text of at most 1000 bytes"));
  CHECK_THROWS_AS(read_text_file(big, "scene", 1000), InputError);
}
