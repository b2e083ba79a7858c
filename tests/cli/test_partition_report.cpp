// perinom check --ranks R: the partition the distributed path will use, reported.
#include "../support/cli.hpp"

using namespace cli_test;

TEST_CASE("check --ranks reports each block's owned particles and ghosts", "[cli][partition]") {
  ScratchDir dir;
  std::ofstream(dir.path / "scene.yaml") << tiny_scene;
  // 10 x 10 particles in two Morton blocks (the lower and upper halves): each needs the 3
  // rows next to the cut, 30 particles within one horizon, 60 within two.
  const Outcome o = perinom(dir, "check scene.yaml --ranks 2");
  INFO("stdout: " << o.out << "\nstderr: " << o.err);
  CHECK(o.exit_code == 0);
  CHECK(o.out.find("partition       2 ranks\n") != std::string::npos);
  CHECK(o.out.find("contiguous blocks of a Morton curve: owned 50-50 particles") != std::string::npos);
  CHECK(o.out.find("ghosts within one horizon 30-30 (60.0% of the owned, mean), within two 50-50") != std::string::npos);
  // PT-Scotch's line (or that this build has none): two parts of 50 within its 1% imbalance.
  const bool scotch = o.out.find("PT-Scotch on the bond graph: owned ") != std::string::npos;
  CHECK((scotch || o.out.find("PT-Scotch: not in this build") != std::string::npos));
  if (scotch) CHECK(o.out.find("PT-Scotch on the bond graph: owned 50-50 particles") != std::string::npos);
  require_one_clear_error(perinom(dir, "check scene.yaml --ranks 0"), {"--ranks", "out of range"});
  // More ranks than particles: run refuses it, and check says so (it printed "owned 0-1").
  const Outcome many = perinom(dir, "check scene.yaml --ranks 101");
  CHECK(many.exit_code == 0);
  CHECK(many.out.find("more ranks than the 100 particles: mpirun -np 101 perinom run refuses this scene") !=
        std::string::npos);
  CHECK(many.out.find("owned 0-") == std::string::npos);
}
