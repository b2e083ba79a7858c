// The output folder cannot mislead: an earlier run's files are removed at start (unless
// --keep), and only those (a user's reference.vtu stays, named in a warning); the marker run.incomplete exists exactly while a run is going (a killed run
// leaves it, and its history so far), summary.json carries the status, and no .tmp file
// survives a run that ends by itself, however it ends.
#include <fcntl.h>
#include <unistd.h>

#include "../support/background_run.hpp"
#include "../support/cli.hpp"

using namespace cli_test;

namespace {

/// Every file name in the folder, sorted.
std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

bool has_suffix(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

void require_finished_folder(const fs::path& out) {
  for (const auto& f : files_in(out)) {
    INFO(f);
    CHECK_FALSE(has_suffix(f, ".tmp"));
    CHECK(f != "run.incomplete");
  }
}

}  // namespace

TEST_CASE("a second run in a folder leaves none of an earlier run's files", "[cli]") {
  ScratchDir dir;
  // The earlier run: another name, snapshots every 10 iterations as .vtu and .csv, a line probe.
  std::ofstream(dir.path / "old.yaml") << with(tiny_scene, "name: tiny", "name: old") +
                                               "output: {vtk_every: 10, csv: true}\n";
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  REQUIRE(perinom(dir, "run old.yaml --out out").exit_code == 0);
  const fs::path out = dir.path / "out";
  REQUIRE(fs::exists(out / "old.pvd"));
  REQUIRE(fs::exists(out / "old_000003.vtu"));
  REQUIRE(fs::exists(out / "old_000003.csv"));
  // What a killed run leaves, and a file of the user's own.
  std::ofstream(out / "history.csv.tmp") << "partial";
  std::ofstream(out / "old_000099.vtu.tmp") << "partial";
  std::ofstream(out / "run.incomplete") << "stale";
  std::ofstream(out / "notes.txt") << "mine";

  SECTION("without --keep: only the new run's files and the user's") {
    const Outcome o = perinom(dir, "run scene.yaml --out out --set output.vtk_every=0");
    INFO("stderr: " << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK(o.out.find("removed") != std::string::npos);
    const std::vector<std::string> expected = {"history.csv",  "notes.txt", "perinom.files",  "probe_mid.csv",
                                               "summary.json", "tiny.pvd",  "tiny_000000.vtu"};
    CHECK(files_in(out) == expected);
  }
  SECTION("with --keep: the earlier files stay, the stale temporaries and marker go") {
    const Outcome o = perinom(dir, "run scene.yaml --out out --keep");
    REQUIRE(o.exit_code == 0);
    CHECK(fs::exists(out / "old.pvd"));
    CHECK(fs::exists(out / "old_000003.vtu"));
    CHECK(fs::exists(out / "tiny.pvd"));
    require_finished_folder(out);
  }
}

TEST_CASE("summary.json has the status, and the marker is gone after exit codes 0, 1 and 3", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  struct Case {
    const char* args;
    int exit_code;
    const char* status;
  };
  const Case cases[] = {
      {"", 0, "converged"},
      {"--set solver.max_iterations=5", 1, "not_converged"},
      // Verlet at a hundred times its stable step.
      {"--set solver.type=verlet --set solver.dt=1e-5 --set solver.steps=2000", 3, "diverged"},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION("exit code " << c.exit_code) {
      const Outcome o = perinom(dir, std::string("run scene.yaml --out out ") + c.args);
      INFO("stderr: " << o.err);
      REQUIRE(o.exit_code == c.exit_code);
      const std::string summary = slurp(dir.path / "out" / "summary.json");
      CHECK(summary.find(std::string("\"status\": \"") + c.status + "\"") != std::string::npos);
      require_finished_folder(dir.path / "out");
    }
  }
}

TEST_CASE("a killed run leaves its marker and no summary: it cannot pass for a finished one", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const pid_t pid = test_support::start_in_background(
      dir.path, "'" PERINOM_EXE "' run scene.yaml --out out --threads 1 --set solver.tolerance=1e-300 "
                "--set solver.displacement_tolerance=1e-300 --set solver.max_iterations=1000000000 >/dev/null 2>&1");
  // Killed once the solve is under way (the marker exists; at most 30 s).
  test_support::kill_when(pid, 30.0, [&] { return fs::exists(dir.path / "out" / "run.incomplete"); }, 300);
  CHECK(fs::exists(dir.path / "out" / "run.incomplete"));
  CHECK_FALSE(fs::exists(dir.path / "out" / "summary.json"));
  // The history so far is there (rewritten every few seconds), in whole rows.
  const std::string history = slurp(dir.path / "out" / "history.csv");
  CHECK(history.rfind("iteration,load_factor,residual", 0) == 0);
  CHECK(std::count(history.begin(), history.end(), '\n') >= 2);
  CHECK(history.back() == '\n');
}

TEST_CASE("a run removes only what a perinom run wrote: a user's files named like outputs stay, and are named", "[cli]") {
  // `--out .` in a project folder removed a reference.vtu and a probe_lab.csv of the user's.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const fs::path out = dir.path / "out";
  fs::create_directories(out);
  std::ofstream(out / "reference.vtu") << "mine";
  std::ofstream(out / "probe_lab.csv") << "mine";
  for (int run = 1; run <= 2; ++run) {
    INFO("run " << run);
    const Outcome o = perinom(dir, "run scene.yaml --out out");
    INFO(o.out << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK(slurp(out / "reference.vtu") == "mine");
    CHECK(slurp(out / "probe_lab.csv") == "mine");
    CHECK(o.out.find("perinom: warning: --out out holds 2 file(s) named like perinom's output that no perinom run "
                     "recorded writing there (probe_lab.csv, reference.vtu)") != std::string::npos);
    // The second run removes the first one's 5 files (summary, history, probe, .pvd, .vtu), which its manifest lists.
    CHECK((o.out.find("removed 5 files of an earlier run") != std::string::npos) == (run == 2));
    const std::string manifest = slurp(out / "perinom.files");
    CHECK(manifest.find("tiny_000000.vtu\n") != std::string::npos);
    CHECK(manifest.find("reference.vtu") == std::string::npos);
  }
}

TEST_CASE("a run refuses to write over a user's file it would replace, before it writes anything", "[cli]") {
  // A user's summary.json and history.csv were overwritten while the warning said they were
  // "left in place, and not this run's".
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const fs::path out = dir.path / "out";
  fs::create_directories(out);
  // A stray NAME_000007.vtu, which this run (one snapshot, NAME_000000) does not write, was
  // said to be written over: it is refused as named like the run's files.
  for (const std::string name : {"summary.json", "tiny_000000.vtu", "tiny_000007.vtu"}) {
    INFO(name);
    std::ofstream(out / name) << "mine";
    const Outcome o = perinom(dir, "run scene.yaml --out out");
    CHECK(o.exit_code == 2);
    CHECK(o.err.find("--out out holds " + name + ", which no perinom run recorded writing there and which is named "
                     "like this run's output files") != std::string::npos);
    CHECK(o.err.find("would write over") == std::string::npos);
    CHECK(slurp(out / name) == "mine");
    CHECK(files_in(out) == std::vector<std::string>{name});  // no marker, no output
    fs::remove(out / name);
  }
}

TEST_CASE("after a killed run the files written since its marker are removed, older ones stay", "[cli]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const fs::path out = dir.path / "out";
  fs::create_directories(out);
  // A user's file from an hour ago, the killed run's marker from ten minutes ago and its
  // snapshot from five (times set, so that no clock tick can tie them).
  std::ofstream(out / "old_000001.vtu") << "mine";
  std::ofstream(out / "run.incomplete") << "perinom run in progress";
  std::ofstream(out / "tiny_000007.vtu") << "killed";
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(out / "old_000001.vtu", now - std::chrono::hours(1));
  fs::last_write_time(out / "run.incomplete", now - std::chrono::minutes(10));
  fs::last_write_time(out / "tiny_000007.vtu", now - std::chrono::minutes(5));
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  INFO(o.out << o.err);
  REQUIRE(o.exit_code == 0);
  CHECK_FALSE(fs::exists(out / "tiny_000007.vtu"));
  CHECK(slurp(out / "old_000001.vtu") == "mine");
  CHECK(o.out.find("(old_000001.vtu): left in place") != std::string::npos);
  require_finished_folder(out);
}

TEST_CASE("a run into a folder another perinom run is writing is refused with exit 2, naming the process", "[cli]") {
  // A sweep of `--set` runs sharing the default out/NAME: the second removed the first's
  // history and marker, and the folder ended with one run's summary and the other's history.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const pid_t pid = test_support::start_in_background(
      dir.path, "'" PERINOM_EXE "' run scene.yaml --out out --threads 1 --set solver.tolerance=1e-300 "
                "--set solver.displacement_tolerance=1e-300 --set solver.max_iterations=1000000000 >/dev/null 2>&1");
  const fs::path marker = dir.path / "out" / "run.incomplete";
  for (int k = 0; k < 300 && !fs::exists(marker); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  REQUIRE(fs::exists(marker));
  const Outcome second = perinom(dir, "run scene.yaml --out out");
  test_support::kill_when(pid, 0.0, [] { return true; }, 0);
  INFO(second.out << second.err);
  CHECK(second.exit_code == 2);
  CHECK(second.err.find("--out out: another perinom run (process " + std::to_string(pid) +
                        ") is writing this folder") != std::string::npos);
  // Killed, its marker is stale: the next run goes ahead and replaces the killed run's files.
  const Outcome third = perinom(dir, "run scene.yaml --out out");
  INFO(third.out << third.err);
  CHECK(third.exit_code == 0);
  require_finished_folder(dir.path / "out");
}

TEST_CASE("a killed run its parent has not reaped yet is not taken for a run going on", "[cli]") {
  // `--restart` right after `timeout -s KILL` was refused: "another perinom run (process N)
  // is writing this folder", N a zombie. A perinom that ended (the program without arguments
  // exits at once) and is not waited for stands for it, its pid in the marker.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1), ::dup2(null, 2);
    ::execl(PERINOM_EXE, "perinom", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto zombie = [&] {
    const std::string stat = slurp("/proc/" + std::to_string(pid) + "/stat");
    const auto at = stat.rfind(')');
    return at != std::string::npos && at + 2 < stat.size() && stat[at + 2] == 'Z';
  };
  for (int k = 0; k < 200 && !zombie(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  REQUIRE(zombie());
  fs::create_directories(dir.path / "out");
  std::ofstream(dir.path / "out" / "run.incomplete") << "perinom run in progress (process " << pid << "); ...\n";
  const Outcome o = perinom(dir, "run scene.yaml --out out");
  ::waitpid(pid, nullptr, 0);
  INFO(o.out << o.err);
  CHECK(o.exit_code == 0);
  require_finished_folder(dir.path / "out");
}

TEST_CASE("a run that cannot write its list of files leaves its marker, and the next run here still knows them", "[cli]") {
  // On a full disk the list was left empty under its name and the marker removed: the next
  // run refused the first one's files as no run's. A folder in the list's .tmp place fails
  // its write the same way (and was renamed over the list).
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  fs::create_directories(dir.path / "out" / "perinom.files.tmp");
  const Outcome first = perinom(dir, "run scene.yaml --out out");
  INFO("first stderr: " << first.err);
  REQUIRE(first.exit_code == 0);
  CHECK(first.err.find("could not be written") != std::string::npos);
  CHECK(fs::exists(dir.path / "out" / "run.incomplete"));
  CHECK_FALSE(fs::exists(dir.path / "out" / "perinom.files"));
  fs::remove(dir.path / "out" / "perinom.files.tmp");
  const Outcome second = perinom(dir, "run scene.yaml --out out");
  INFO("second stderr: " << second.err);
  CHECK(second.exit_code == 0);
  require_finished_folder(dir.path / "out");
}

TEST_CASE("an error after the folder is prepared is said in summary.json, and without a summary the marker stays", "[cli]") {
  // A checkpoint that cannot be written (a folder holds its name) ended the run with exit 2,
  // a history and no summary, the marker gone: a state the folder's rules did not describe.
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  fs::create_directories(dir.path / "out" / "checkpoint.bin");
  const Outcome o = perinom(dir, "run scene.yaml --out out --set output.checkpoint_every=10");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  REQUIRE(o.exit_code == 2);
  const std::string summary = slurp(dir.path / "out" / "summary.json");
  CHECK(summary.find("\"status\": \"error\"") != std::string::npos);
  CHECK(summary.find("\"exit_code\": 2") != std::string::npos);
  CHECK(summary.find("cannot write checkpoint") != std::string::npos);
  require_finished_folder(dir.path / "out");
  // A summary that cannot be written either (a folder holds its name): the marker stays.
  ScratchDir other;
  std::ofstream(other.path / "scene.yaml") << tiny_scene;
  fs::create_directories(other.path / "out" / "checkpoint.bin");
  fs::create_directories(other.path / "out" / "summary.json");
  const Outcome none = perinom(other, "run scene.yaml --out out --set output.checkpoint_every=10 --keep");
  INFO("stdout: " << none.out << "\nstderr: " << none.err);
  CHECK(none.exit_code == 2);
  CHECK(fs::exists(other.path / "out" / "run.incomplete"));
  CHECK(none.err.find("summary.json could not be written; run.incomplete stays") != std::string::npos);
}
