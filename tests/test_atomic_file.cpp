// io/atomic_file: single files and sets of files are all-or-nothing; stale temporaries of dead
// processes are cleared.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "adjoin/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "cli_helpers.hpp"

namespace fs = std::filesystem;
using adjoin::AtomicFile;
using adjoin::FileSet;
using adjoin::test::slurp;

namespace {

fs::path fresh_dir(const std::string& name) {
  const auto dir = fs::path(ADJOIN_TEST_TMP) / "atomic_file" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int count_temporaries(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp.") != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE("AtomicFile replaces the target only on commit", "[atomic_file]") {
  const auto dir = fresh_dir("single");
  std::ofstream(dir / "a.txt") << "old";
  {
    AtomicFile f(dir / "a.txt");
    f.stream() << "new";
    CHECK(slurp(dir / "a.txt") == "old");
    CHECK(count_temporaries(dir) == 1);
  }  // destroyed without commit
  CHECK(slurp(dir / "a.txt") == "old");
  CHECK(count_temporaries(dir) == 0);
  AtomicFile f(dir / "a.txt");
  f.stream() << "new";
  f.commit();
  CHECK(slurp(dir / "a.txt") == "new");
  CHECK(count_temporaries(dir) == 0);
}

TEST_CASE("a FileSet is all or none, and leaves exactly its own members", "[atomic_file]") {
  const auto dir = fresh_dir("set");
  std::ofstream(dir / "summary.json") << "old summary";
  std::ofstream(dir / "series.csv") << "old series";
  std::ofstream(dir / "extra.csv") << "old extra";
  std::ofstream(dir / "notes.txt") << "not a member";

  SECTION("a write error in one member replaces nothing") {
    {
      FileSet set(dir, {"summary.json", "series.csv", "extra.csv"});
      set.open("series.csv") << "new series";
      std::ostream& summary = set.open("summary.json");
      summary << "new summary";
      summary.setstate(std::ios::badbit);  // what a full disk does to the stream
      CHECK_THROWS_AS(set.commit(), adjoin::InputError);
    }
    CHECK(slurp(dir / "summary.json") == "old summary");
    CHECK(slurp(dir / "series.csv") == "old series");
    CHECK(slurp(dir / "extra.csv") == "old extra");
    CHECK(count_temporaries(dir) == 0);
  }
  SECTION("a commit writes its members and removes the members it did not write") {
    FileSet set(dir, {"summary.json", "series.csv", "extra.csv"});
    set.open("series.csv") << "new series";
    set.open("summary.json") << "new summary";
    const auto written = set.commit();
    REQUIRE(written.size() == 2);
    CHECK(written[0] == dir / "series.csv");
    CHECK(slurp(dir / "summary.json") == "new summary");
    CHECK(slurp(dir / "series.csv") == "new series");
    CHECK(!fs::exists(dir / "extra.csv"));
    CHECK(slurp(dir / "notes.txt") == "not a member");
    CHECK(count_temporaries(dir) == 0);
  }
}

TEST_CASE("temporaries of dead processes are removed, those of live ones kept", "[atomic_file]") {
  const auto dir = fresh_dir("stale");
  // pid 1 is alive; 4194303 is above the default pid_max of most systems and at the top of
  // the largest, so it names no process here.
  std::ofstream(dir / "a.txt.tmp.4194303") << "half";
  std::ofstream(dir / "a.txt.tmp.1") << "in progress elsewhere";
  std::ofstream(dir / "b.txt.tmp.4194303") << "another target's";
  std::ofstream(dir / "a.txt.tmp.notapid") << "not ours";
  AtomicFile f(dir / "a.txt");
  f.stream() << "x";
  f.commit();
  CHECK(!fs::exists(dir / "a.txt.tmp.4194303"));
  CHECK(fs::exists(dir / "a.txt.tmp.1"));
  CHECK(fs::exists(dir / "b.txt.tmp.4194303"));  // cleared when b.txt is next written
  CHECK(fs::exists(dir / "a.txt.tmp.notapid"));
}
