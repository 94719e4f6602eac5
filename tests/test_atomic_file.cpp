// io/atomic_file: single files and sets of files are all-or-nothing; stale temporaries of dead
// processes are cleared; devices and pipes are written in place, never replaced.
// io/output_place: an output folder is checked before any work and left as it was on failure.
#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "adjoin/core/errors.hpp"
#include "adjoin/io/atomic_file.hpp"
#include "adjoin/io/output_place.hpp"
#include "cli_helpers.hpp"

namespace fs = std::filesystem;
using adjoin::AtomicFile;
using adjoin::FileSet;
using adjoin::test::run_cli;
using adjoin::test::shell_word;
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

// A symbolic link in `dir` to a system device: written through, it reaches the device; a
// writer that renamed over it would replace the link (never the device itself), so the tests
// that must fail without the in-place writing cannot damage /dev.
fs::path link_to(const fs::path& dir, const std::string& name, const fs::path& device) {
  const fs::path link = dir / name;
  fs::create_symlink(device, link);
  return link;
}

bool still_links_to_a_device(const fs::path& link) {
  return fs::is_symlink(fs::symlink_status(link)) && fs::is_character_file(fs::status(link));
}

// Reads everything written into a FIFO while a command runs (on a thread, so a writer larger
// than the pipe's buffer never blocks): open() first, without blocking, so the writer's
// open() finds a reader.
class FifoReader {
 public:
  explicit FifoReader(const fs::path& fifo) : fd_(::open(fifo.c_str(), O_RDONLY | O_NONBLOCK)) {
    REQUIRE(fd_ >= 0);
    thread_ = std::thread([this] {
      for (;;) {
        const bool last = done_.load();  // read once more after the writer is done
        pollfd p{fd_, POLLIN, 0};
        ::poll(&p, 1, 50);
        char buffer[65536];
        ssize_t n;
        while ((n = ::read(fd_, buffer, sizeof buffer)) > 0) text_.append(buffer, static_cast<std::size_t>(n));
        if (last) return;
      }
    });
  }
  // Everything read, once the writer has finished.
  std::string finish() {
    done_ = true;
    thread_.join();
    ::close(fd_);
    return text_;
  }

 private:
  int fd_;
  std::atomic<bool> done_{false};
  std::string text_;
  std::thread thread_;
};

// `device` (a path in /dev) must still be a character device with these numbers; if a
// regression replaced it with a file, it is made again (root only) and the test fails.
void require_device_intact(const fs::path& device, unsigned major_number, unsigned minor_number) {
  struct stat st {};
  const bool intact = ::stat(device.c_str(), &st) == 0 && S_ISCHR(st.st_mode) && major(st.st_rdev) == major_number &&
                      minor(st.st_rdev) == minor_number;
  if (!intact && ::geteuid() == 0) {
    ::unlink(device.c_str());
    ::mknod(device.c_str(), S_IFCHR | 0666, makedev(major_number, minor_number));
    ::chmod(device.c_str(), 0666);
  }
  INFO(device.string() << " was replaced (and has been made again)");
  REQUIRE(intact);
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

TEST_CASE("AtomicFile writes a device or a pipe in place and never renames over it", "[atomic_file]") {
  const auto dir = fresh_dir("in_place");

  SECTION("a FIFO receives the content and stays a FIFO") {
    const fs::path fifo = dir / "pipe";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    FifoReader reader(fifo);
    {
      AtomicFile f(fifo);
      CHECK(f.in_place());
      f.stream() << "period,psa\n0.1,0.25\n";
      f.commit();
    }
    CHECK(reader.finish() == "period,psa\n0.1,0.25\n");
    CHECK(fs::is_fifo(fs::symlink_status(fifo)));
    CHECK(count_temporaries(dir) == 0);
  }
  SECTION("a full device is a write error with the system's reason, and stays a device") {
    const fs::path full = link_to(dir, "full", "/dev/full");
    AtomicFile f(full);
    f.stream() << std::string(200000, 'x');  // more than the writer's buffer
    CHECK_THROWS_WITH(f.commit(), Catch::Contains(full.string() + ": write failed: No space left on device"));
    CHECK(still_links_to_a_device(full));
    CHECK(count_temporaries(dir) == 0);
  }
  SECTION("the null device takes everything, and stays a device") {
    const fs::path null = link_to(dir, "null", "/dev/null");
    AtomicFile f(null);
    f.stream() << std::string(200000, 'x');
    f.commit();
    CHECK(still_links_to_a_device(null));
    CHECK(count_temporaries(dir) == 0);
  }
  SECTION("content written in place cannot be taken back: restart() is refused") {
    const fs::path null = link_to(dir, "null", "/dev/null");
    FileSet set(dir, {"null"});
    set.open("null") << "first try";
    CHECK_THROWS_WITH(set.restart(), Catch::Contains("null: is a character device, written in place"));
  }
  SECTION("a folder is not a file to write") {
    fs::create_directories(dir / "d.csv");
    CHECK_THROWS_WITH(AtomicFile(dir / "d.csv"), Catch::Contains("d.csv: is a folder"));
    CHECK(count_temporaries(dir) == 0);
  }
  SECTION("a set leaves alone a pipe named like a member it does not write") {
    const fs::path fifo = dir / "energy.csv";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    FileSet set(dir, {"summary.json", "energy.csv"});
    set.open("summary.json") << "{}";
    set.commit();
    CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  }
}

TEST_CASE("commands write a device or pipe named by --out in place: a full device is exit 2", "[atomic_file][cli]") {
  const auto dir = fresh_dir("commands_in_place");
  const fs::path record = fs::path(ADJOIN_SOURCE_DIR) / "records" / "real" / "peer" / "RSN175_IMPVALL.H_H-E12140.AT2";
  const std::vector<std::string> commands = {"spectrum " + shell_word(record), "record process " + shell_word(record),
                                             "record fourier " + shell_word(record),
                                             "synth --pga 0.3 --duration 2 --dt 0.01 --seed 1"};
  const fs::path full = link_to(dir, "full", "/dev/full"), null = link_to(dir, "null", "/dev/null");
  for (const auto& command : commands) {
    INFO(command);
    auto r = run_cli(command + " --out " + shell_word(full));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::StartsWith("error: ") && Catch::Contains("No space left on device"));
    CHECK(still_links_to_a_device(full));
    r = run_cli(command + " --out " + shell_word(null));
    CHECK(r.status == 0);
    CHECK(still_links_to_a_device(null));
    CHECK(count_temporaries(dir) == 0);
  }
  // A FIFO read while the command writes: the CSV arrives, the FIFO stays.
  const fs::path fifo = dir / "spectrum.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  FifoReader reader(fifo);
  const auto r = run_cli("spectrum " + shell_word(record) + " --out " + shell_word(fifo));
  const std::string text = reader.finish();
  CHECK(r.status == 0);
  CHECK_THAT(text, Catch::StartsWith("period,damping,sd,sv,sa,psv,psa\n"));
  CHECK(fs::is_fifo(fs::symlink_status(fifo)));
  CHECK(count_temporaries(dir) == 0);

  // The system's own devices, only once the links above show the writing in place works (a
  // regression would otherwise replace them: as root, /dev is writable).
  REQUIRE(still_links_to_a_device(full));
  REQUIRE(still_links_to_a_device(null));
  const auto on_full = run_cli("spectrum " + shell_word(record) + " --out /dev/full");
  CHECK(on_full.status == 2);
  CHECK_THAT(on_full.err, Catch::Contains("/dev/full: write failed: No space left on device"));
  require_device_intact("/dev/full", 1, 7);
  CHECK(run_cli("spectrum " + shell_word(record) + " --out /dev/null").status == 0);
  require_device_intact("/dev/null", 1, 3);
}

TEST_CASE("an output folder is checked before any work: files and devices are refused", "[atomic_file]") {
  const auto dir = fresh_dir("check_folder");
  std::ofstream(dir / "file") << "a file";
  using adjoin::check_output_folder;
  CHECK_NOTHROW(check_output_folder(dir));
  CHECK_NOTHROW(check_output_folder(dir / "new" / "deeper"));
  CHECK_THROWS_WITH(check_output_folder(dir / "file"), Catch::Contains("--out " + (dir / "file").string() + ": is a file, not a folder"));
  CHECK_THROWS_WITH(check_output_folder(dir / "file" / "out", "--out"),
                    Catch::Contains("cannot create the output folder: " + (dir / "file").string() + " is a file, not a folder"));
  CHECK_THROWS_WITH(check_output_folder("/dev/null"), Catch::Contains("--out /dev/null: is a character device, not a folder"));
  CHECK_THROWS_WITH(check_output_folder("/dev/null/x", "--plot"),
                    Catch::Contains("--plot /dev/null/x: cannot create the output folder: /dev/null is a character device"));
  CHECK_THROWS_WITH(check_output_folder(""), Catch::Contains("expected a folder name"));
}

TEST_CASE("a set's folder exists only once the set is committed", "[atomic_file]") {
  const auto dir = fresh_dir("set_folder");
  {
    FileSet set(dir / "a" / "b", {"summary.json"});
    set.open("summary.json") << "a run that fails";
  }  // not committed: the folders it made are gone
  CHECK(!fs::exists(dir / "a"));
  {
    FileSet set(dir / "a" / "b", {"summary.json"});
    set.open("summary.json") << "{}";
    set.commit();
  }
  CHECK(slurp(dir / "a" / "b" / "summary.json") == "{}");
  {
    fs::create_directories(dir / "kept");
    FileSet set(dir / "kept" / "new", {"summary.json"});
    set.open("summary.json") << "fails";
  }
  CHECK(fs::is_directory(dir / "kept"));  // it was there before
  CHECK(!fs::exists(dir / "kept" / "new"));
}
