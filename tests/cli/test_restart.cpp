// `perinom run SCENE --restart DIR`: a run resumed from a checkpoint written part-way ends
// with the files of the uninterrupted run, bit for bit (ADR, Verlet, a thin plate, an LBC
// load path; resumed in a folder holding only the checkpoint, in place in a folder the run
// went on writing, and into another folder), and a checkpoint that is not this scene's, or
// not whole, is refused.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "../support/cli.hpp"

using namespace cli_test;

namespace {

const std::string biaxial = "'" PERINOM_SOURCE_DIR "/examples/biaxial_compression.yaml'";
const std::string bar = "'" PERINOM_SOURCE_DIR "/examples/vibrating_bar.yaml'";

/// The summary from "solver" to "wall_time": iterations, residual, reactions, plasticity and
/// probes, every number in the shortest text that reads back bit for bit; without the lines
/// of wall times inside it (a cracking run's solver.fracture: *_seconds*, *_step_ratio).
std::string results_of(const std::string& summary) {
  const auto from = summary.find("\"solver\""), to = summary.find("\"wall_time\"");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  std::istringstream in(summary.substr(from, to - from));
  std::string out, line;
  while (std::getline(in, line))
    if (line.find("_seconds") == std::string::npos && line.find("_step_ratio\"") == std::string::npos) out += line + "\n";
  return out;
}

/// load_steps.csv without its wall-time column (seconds, the tenth).
std::string without_seconds(const std::string& csv) {
  std::string out, line;
  std::istringstream in(csv);
  while (std::getline(in, line)) {
    std::size_t start = 0;
    for (int k = 0; k < 9; ++k) start = line.find(',', start) + 1;
    const std::size_t end = line.find(',', start);
    out += line.substr(0, start) + (end == std::string::npos ? "" : line.substr(end + 1)) + "\n";
  }
  return out;
}

/// The manifest's names but checkpoint.bin (which only a checkpointing run writes).
std::string without_checkpoint(std::string manifest) {
  const std::string line = "checkpoint.bin\n";
  if (const auto at = manifest.find(line); at != std::string::npos) manifest.erase(at, line.size());
  return manifest;
}

/// Every file of the uninterrupted run's folder is in `other` with the same bytes (the
/// snapshots' .vtu and .csv, the .pvd, the histories, the probes' files, the manifest but its
/// checkpoint), the summary's
/// results and the step table's numbers but for their wall times.
void require_same_results(const fs::path& reference, const fs::path& other) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(reference)) names.insert(e.path().filename().string());
  CHECK(names.count("summary.json"));
  for (const auto& name : names) {
    INFO(other / name);
    REQUIRE(fs::exists(other / name));
    const std::string a = slurp(reference / name), b = slurp(other / name);
    if (name == "summary.json") CHECK(results_of(a) == results_of(b));
    else if (name == "load_steps.csv") CHECK(without_seconds(a) == without_seconds(b));
    else if (name == "perinom.files") CHECK(without_checkpoint(a) == without_checkpoint(b));
    else CHECK(a == b);
  }
  for (const auto& e : fs::directory_iterator(other)) {
    const std::string name = e.path().filename().string();
    INFO(name);
    CHECK((names.count(name) || name == "checkpoint.bin"));
  }
}

/// A whole number after "key": in a summary.
long number_after(const std::string& summary, const std::string& key) {
  const auto at = summary.find("\"" + key + "\": ");
  REQUIRE(at != std::string::npos);
  return std::stol(summary.substr(at + key.size() + 4));
}

void require_ok(const Outcome& o) {
  INFO(o.err);
  REQUIRE(o.exit_code == 0);
}

}  // namespace

TEST_CASE("ADR resumed from a checkpoint copied aside part-way ends bit for bit as the uninterrupted run", "[cli][checkpoint]") {
  ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << tiny_scene;
  const std::string sets = " --set output.csv=true --set solver.tolerance=1e-10 --set solver.displacement_tolerance=1e-10";
  require_ok(perinom(d, "run scene.yaml --out reference" + sets));
  const long n = number_after(slurp(d.path / "reference" / "summary.json"), "iterations");
  REQUIRE(n > 100);
  REQUIRE(n % 10 != 0);  // (history_every 10: the last row is the one added at the end)
  // The only checkpoint part-way, and at the iteration it converges on: that resumed run stops
  // at once, its last history row (damping, reactions) and the summary's residual force from
  // the checkpoint's state (they read 0, 0, 0 and null).
  for (const long k : {n / 2 + 1, n}) {
    INFO("checkpoint at iteration " << k << " of " << n);
    const std::string written = "written" + std::to_string(k), resumed = "resumed" + std::to_string(k);
    require_ok(perinom(d, "run scene.yaml --out " + written + " --set output.checkpoint_every=" + std::to_string(k) + sets));
    require_same_results(d.path / "reference", d.path / written);  // writing checkpoints changes nothing
    // The run interrupted after the checkpoint: a folder with only it, resumed in place.
    fs::create_directories(d.path / resumed);
    fs::copy_file(d.path / written / "checkpoint.bin", d.path / resumed / "checkpoint.bin");
    const Outcome o = perinom(d, "run scene.yaml --restart " + resumed + sets);
    require_ok(o);
    const std::string from = resumed + "/checkpoint.bin (iteration " + std::to_string(k) + ")";
    CHECK(o.out.find("perinom: resuming from " + from) != std::string::npos);
    CHECK(slurp(d.path / resumed / "summary.json").find("\"restarted_from\": \"" + from + "\"") != std::string::npos);
    require_same_results(d.path / "reference", d.path / resumed);
  }
}

TEST_CASE("Verlet resumed in place, in a folder the killed run went on writing, ends bit for bit", "[cli][checkpoint]") {
  ScratchDir d;
  const std::string sets = " --set solver.steps=300 --set output.vtk_every=100 --set output.csv=true";
  require_ok(perinom(d, "run " + bar + " --out reference --threads 2" + sets));
  require_ok(perinom(d, "run " + bar + " --out killed --threads 2 --set output.checkpoint_every=160" + sets));
  // The folder as a run killed after its last snapshot would leave it, the checkpoint of
  // step 160 (listing the snapshot of step 100) in it: resuming removes what came later.
  fs::remove(d.path / "killed" / "summary.json");
  // On one thread where the others ran on two: the sums give the same bits for any count.
  const Outcome o = perinom(d, "run " + bar + " --restart killed --threads 1" + sets);
  require_ok(o);
  CHECK(o.out.find("resuming from killed/checkpoint.bin (step 160, t = ") != std::string::npos);
  CHECK(o.out.find("removed 6 files of an earlier run") != std::string::npos);  // 2 snapshots (.vtu, .csv), .pvd, histories
  require_same_results(d.path / "reference", d.path / "killed");
}

TEST_CASE("a cracking run resumed from a checkpoint ends bit for bit: broken bonds, armed criterion, lowered step",
          "[cli][checkpoint][fracture]") {
  // SENT (instability criterion: armed at one find, s_hg_max fixed then) and Kalthoff-Winkler
  // (stress criterion), each checkpointed after bonds have broken and before the run ends.
  const std::string sent = "'" PERINOM_SOURCE_DIR "/examples/sent.yaml'";
  const std::string kw = "'" PERINOM_SOURCE_DIR "/examples/kalthoff_winkler.yaml'";
  for (const auto& [scene, every] : {std::pair{sent, 700}, std::pair{kw, 120}}) {
    INFO(scene);
    ScratchDir d;
    const std::string sets = " --set output.vtk_every=100 --set output.csv=true";
    require_ok(perinom(d, "run " + scene + " --out reference" + sets));
    const std::string reference = slurp(d.path / "reference" / "summary.json");
    require_ok(perinom(d, "run " + scene + " --out written --set output.checkpoint_every=" + std::to_string(every) + sets));
    require_same_results(d.path / "reference", d.path / "written");
    // Bonds broke before the checkpoint and after it: the history's broken_bonds column.
    const std::string history = slurp(d.path / "reference" / "history.csv");
    std::istringstream rows(history);
    std::string header, line;
    std::getline(rows, header);
    long at_checkpoint = -1, at_end = -1;
    while (std::getline(rows, line)) {
      const long step = std::stol(line);
      const long broken = std::lround(std::stod(line.substr(line.find_last_of(',', line.find_last_of(',') - 1) + 1)));
      if (step == every) at_checkpoint = broken;
      at_end = broken;
    }
    CHECK(at_checkpoint > 0);
    CHECK(at_end > at_checkpoint);
    const Outcome o = perinom(d, "run " + scene + " --restart written --out resumed" + sets);
    require_ok(o);
    CHECK(o.out.find("resuming from written/checkpoint.bin (step " + std::to_string(every) + ", ") != std::string::npos);
    require_same_results(d.path / "reference", d.path / "resumed");
    CHECK(results_of(slurp(d.path / "resumed" / "summary.json")) == results_of(reference));
  }
}

TEST_CASE("a load path that breaks bonds resumed after the break ends bit for bit", "[cli][checkpoint][fracture][load_path]") {
  // The brittle bar without grips: it fails at load step 118 and breaks 4 bonds more at 137
  // and 165; resumed at 120, the restored bonds, ADR's density after them, the load the
  // residual is measured against and the step count must all be the run's.
  ScratchDir d;
  const std::string scene = "'" PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml' --set 'damage.no_fail=[]'";
  require_ok(perinom(d, "run " + scene + " --out reference"));
  require_ok(perinom(d, "run " + scene + " --out written --set output.checkpoint_every=120"));
  require_same_results(d.path / "reference", d.path / "written");
  const Outcome o = perinom(d, "run " + scene + " --restart written --out resumed");
  require_ok(o);
  CHECK(o.out.find("resuming from written/checkpoint.bin (load step 120 of stage 1)") != std::string::npos);
  require_same_results(d.path / "reference", d.path / "resumed");
  CHECK(slurp(d.path / "reference" / "summary.json").find("\"breaking_steps\": 3") != std::string::npos);
}

TEST_CASE("a load path with softening bonds resumed mid-softening ends bit for bit", "[cli][checkpoint][fracture][load_path]") {
  // The bar cracking in a band with G_f = 50 N/m (tests/cli/test_quasi_static_fracture.cpp):
  // resumed at load step 150 of 200 (75 um), past the peak with the bonds softening, the restored
  // bonds must carry their committed openings (kappa), or the softening and the energy
  // account (dissipated_energy) would differ.
  ScratchDir d;
  const std::string scene = "'" PERINOM_SOURCE_DIR "/examples/brittle_bar.yaml' --set damage.fracture_energy=50"
                            " --set 'damage.no_fail.0.region.box.max=[0.0435, 1.0]'"
                            " --set 'damage.no_fail.1.region.box.min=[0.0565, -1.0]' --set stages.0.steps=200"
                            " --set stages.0.boundary.2.displacement.x=1.0e-4";
  require_ok(perinom(d, "run " + scene + " --out reference"));
  require_ok(perinom(d, "run " + scene + " --out written --set output.checkpoint_every=150"));
  require_same_results(d.path / "reference", d.path / "written");
  const Outcome o = perinom(d, "run " + scene + " --restart written --out resumed");
  require_ok(o);
  CHECK(o.out.find("resuming from written/checkpoint.bin (load step 150 of stage 1)") != std::string::npos);
  require_same_results(d.path / "reference", d.path / "resumed");
  const std::string summary = slurp(d.path / "reference" / "summary.json");
  CHECK(number_after(summary, "softening_bonds_spent") < number_after(summary, "bonds_broken"));
  CHECK(number_after(summary, "bonds_broken") > 100);
}

TEST_CASE("a thin plate in Verlet resumed from a checkpoint ends bit for bit", "[cli][checkpoint]") {
  ScratchDir d;
  const std::string plate = "'" PERINOM_SOURCE_DIR "/examples/thin_plate_clamped.yaml'";
  const std::string sets = " --set solver.type=verlet --set solver.steps=200 --set discretization.dx=0.05"
                           " --set output.csv=true";
  require_ok(perinom(d, "run " + plate + " --out reference" + sets));
  require_ok(perinom(d, "run " + plate + " --out written --set output.checkpoint_every=120" + sets));
  const Outcome o = perinom(d, "run " + plate + " --restart written --out resumed" + sets);
  require_ok(o);
  CHECK(o.out.find("resuming from written/checkpoint.bin (step 120, ") != std::string::npos);
  require_same_results(d.path / "reference", d.path / "resumed");
}

TEST_CASE("an LBC load path resumed into another folder ends bit for bit, its earlier snapshots copied", "[cli][checkpoint][load_path]") {
  ScratchDir d;
  const std::string sets = " --set stages.0.steps=3 --set stages.1.steps=3 --set discretization.dx=0.005"
                           " --set output.vtk_every=1 --set output.csv=true";
  require_ok(perinom(d, "run " + biaxial + " --out reference" + sets));
  require_ok(perinom(d, "run " + biaxial + " --out written --set output.checkpoint_every=4" + sets));
  const Outcome o = perinom(d, "run " + biaxial + " --restart written --out resumed" + sets);
  require_ok(o);
  CHECK(o.out.find("resuming from written/checkpoint.bin (load step 1 of stage 2)") != std::string::npos);
  CHECK(slurp(d.path / "resumed" / "summary.json").find("\"particles_yielded\": 100") != std::string::npos);
  require_same_results(d.path / "reference", d.path / "resumed");
  // No checkpoint fell after the resumed step: the folder holds the one it resumed from, and
  // can be resumed again (it had none, and was refused: "the folder holds no checkpoint").
  REQUIRE(fs::exists(d.path / "resumed" / "checkpoint.bin"));
  require_ok(perinom(d, "run " + biaxial + " --restart resumed --out again" + sets));
  require_same_results(d.path / "reference", d.path / "again");
}

TEST_CASE("an LBC load path checkpointed at its last step resumes to the same files, its .pvd and summary included",
          "[cli][checkpoint][load_path]") {
  // Nothing is left to balance: the .pvd used to be written at the next snapshot only (none
  // came; in place, the old one was removed), and the summary lost the last balance's forces.
  ScratchDir d;
  const std::string sets = " --set stages.0.steps=3 --set stages.1.steps=3 --set discretization.dx=0.005"
                           " --set output.vtk_steps=[2,6]";
  require_ok(perinom(d, "run " + biaxial + " --out reference" + sets));
  require_ok(perinom(d, "run " + biaxial + " --out written --set output.checkpoint_every=6" + sets));
  require_ok(perinom(d, "run " + biaxial + " --restart written --out resumed --set output.checkpoint_every=6" + sets));
  require_same_results(d.path / "reference", d.path / "resumed");
  require_ok(perinom(d, "run " + biaxial + " --restart written --set output.checkpoint_every=6" + sets));  // in place
  require_same_results(d.path / "reference", d.path / "written");
}

TEST_CASE("a checkpoint whose snapshots' files are gone from its folder is refused, naming the file", "[cli][checkpoint][load_path]") {
  // A snapshot's .csv (output.csv) deleted from the folder: the resumed run ended with exit 0
  // and a folder without it. Its .vtu was refused already.
  ScratchDir d;
  const std::string sets = " --set stages.0.steps=3 --set stages.1.steps=3 --set discretization.dx=0.005"
                           " --set output.vtk_every=1 --set output.csv=true --set output.checkpoint_every=4";
  require_ok(perinom(d, "run " + biaxial + " --out written" + sets));
  std::string vtu;  // a snapshot the checkpoint lists (of load step 1)
  for (const auto& e : fs::directory_iterator(d.path / "written"))
    if (e.path().extension() == ".vtu" && (vtu.empty() || e.path().filename().string() < vtu)) vtu = e.path().filename().string();
  REQUIRE(!vtu.empty());
  const std::string csv = vtu.substr(0, vtu.size() - 4) + ".csv";
  REQUIRE(fs::exists(d.path / "written" / csv));
  SECTION("its .csv") {
    fs::remove(d.path / "written" / csv);
    require_one_clear_error(perinom(d, "run " + biaxial + " --restart written --out resumed" + sets),
                            {"--restart written:", "also wrote as " + csv, "which the folder does not hold"});
  }
  SECTION("its .vtu") {
    fs::remove(d.path / "written" / vtu);
    require_one_clear_error(perinom(d, "run " + biaxial + " --restart written --out resumed" + sets),
                            {"--restart written:", "the snapshot " + vtu + ", which the folder does not hold"});
  }
  SECTION("both there: resumed") { require_ok(perinom(d, "run " + biaxial + " --restart written --out resumed" + sets)); }
}

TEST_CASE("a run resumed with output.csv turned on resumes again: its earlier snapshots are not asked for a .csv", "[cli][checkpoint][load_path]") {
  // The flag is each snapshot's: written by the scene's output.csv alone, the resumed run's
  // checkpoint at step 5 claimed .csv files for steps 1 to 4, which the first run never wrote.
  ScratchDir d;
  const std::string sets = " --set stages.0.steps=3 --set stages.1.steps=3 --set discretization.dx=0.005 --set output.vtk_every=1";
  require_ok(perinom(d, "run " + biaxial + " --out first --set output.checkpoint_every=4" + sets));
  require_ok(perinom(d, "run " + biaxial + " --restart first --out second --set output.csv=true --set output.checkpoint_every=5" + sets));
  const Outcome o = perinom(d, "run " + biaxial + " --restart second --out third --set output.csv=true" + sets);
  INFO(o.out << o.err);
  CHECK(o.out.find("resuming from second/checkpoint.bin (load step 2 of stage 2)") != std::string::npos);
  REQUIRE(o.exit_code == 0);
}

TEST_CASE("a checkpoint of another scene, a damaged one and a folder without one are refused", "[cli][checkpoint]") {
  ScratchDir d;
  std::ofstream(d.path / "scene.yaml") << tiny_scene;
  require_ok(perinom(d, "run scene.yaml --out written --set output.checkpoint_every=50"));
  const fs::path checkpoint = d.path / "written" / "checkpoint.bin";
  const std::string bytes = slurp(checkpoint);
  SECTION("another scene: the key that differs is named") {
    require_one_clear_error(perinom(d, "run scene.yaml --restart written --set material.E=2.0e9"),
                            {"--restart written:", "another scene", "material.E is 1.0e9 in the checkpoint and 2.0e9 in scene.yaml"});
    CHECK(fs::exists(checkpoint));  // refused before the folder is touched
    CHECK(fs::exists(d.path / "written" / "summary.json"));
  }
  SECTION("truncated") {
    std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
    require_one_clear_error(perinom(d, "run scene.yaml --restart written"), {"--restart written:", "damaged or truncated"});
  }
  SECTION("a byte changed") {
    std::string bad = bytes;
    bad[bad.size() / 3] = static_cast<char>(bad[bad.size() / 3] ^ 0x40);
    std::ofstream(checkpoint, std::ios::binary | std::ios::trunc) << bad;
    require_one_clear_error(perinom(d, "run scene.yaml --restart written"), {"checksum does not match"});
  }
  SECTION("no checkpoint") {
    fs::create_directories(d.path / "empty");
    require_one_clear_error(perinom(d, "run scene.yaml --restart empty"), {"--restart empty:", "holds no checkpoint"});
  }
  SECTION("a file or nothing where the folder should be") {
    require_one_clear_error(perinom(d, "run scene.yaml --restart scene.yaml"), {"--restart scene.yaml:", "not a folder"});
    require_one_clear_error(perinom(d, "run scene.yaml --restart nowhere"), {"--restart nowhere:", "no such folder"});
  }
}

TEST_CASE("a checkpoint is refused when the point file under the same scene text has moved a particle", "[cli][checkpoint]") {
  ScratchDir d;
  const auto write_cloud = [&](double shift, double volume = 1e-6) {
    std::ofstream csv(d.path / "cloud.csv");
    csv << "x,y,volume\n";
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        csv << 0.0005 + 0.001 * i + (i + j == 6 ? shift : 0.0) << "," << 0.0005 + 0.001 * j << "," << volume << "\n";
  };
  write_cloud(0.0);
  std::ofstream(d.path / "scene.yaml") << point_file_scene;
  require_ok(perinom(d, "run scene.yaml --out written"));
  require_ok(perinom(d, "run scene.yaml --restart written --out again"));  // the same cloud resumes
  write_cloud(1e-5);
  require_one_clear_error(perinom(d, "run scene.yaml --restart written --out moved"),
                          {"--restart written:", "particles are not where the scene places them"});
  // The volumes edited, the positions kept: a Verlet run so resumed ended with exit 0 at an
  // answer neither file gives.
  write_cloud(0.0, 1.2e-6);
  require_one_clear_error(perinom(d, "run scene.yaml --restart written --out heavier"),
                          {"--restart written: the text of the body's files (geometry.points ",
                           "cloud.csv) is not, byte for byte, that of the files the checkpoint"});
  // The same numbers in other text: refused (the bytes are compared), and not said to be
  // other volumes or facets.
  write_cloud(0.0);
  std::string text = slurp(d.path / "cloud.csv"), spaced;
  for (const char c : text) spaced += c == ',' ? std::string(", ") : std::string(1, c);
  std::ofstream(d.path / "cloud.csv", std::ios::trunc) << spaced;
  const Outcome o = perinom(d, "run scene.yaml --restart written --out spaced");
  require_one_clear_error(o, {"is not, byte for byte, that of the files", "or only the text was rewritten"});
  CHECK(o.err.find("volumes, facets or groups changed") == std::string::npos);
}

TEST_CASE("Newton solves are not checkpointed, and say so", "[cli][checkpoint]") {
  require_rejected(with(tiny_scene, "type: adr", "type: newton") + "output: {checkpoint_every: 10}\n",
                   {"output.checkpoint_every", "Newton solves are not checkpointed"});
}

TEST_CASE("a cracking Verlet run resumed at its last step reports the step it ended at", "[cli][checkpoint][fracture]") {
  // No step is left to run: final_time_step read 0 ("ended at dt = 0 s").
  ScratchDir d;
  const std::string sent = "'" PERINOM_SOURCE_DIR "/examples/sent.yaml' --set solver.steps=800 --set output.vtk_every=400";
  require_ok(perinom(d, "run " + sent + " --out written --set output.checkpoint_every=800"));
  const double ended = json_number(slurp(d.path / "written" / "summary.json"), "final_time_step");
  REQUIRE(ended > 0.0);
  require_ok(perinom(d, "run " + sent + " --restart written --out resumed --set output.checkpoint_every=800"));
  CHECK(json_number(slurp(d.path / "resumed" / "summary.json"), "final_time_step") == ended);
}
