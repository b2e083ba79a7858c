#pragma once
/// @file The scene's bond breaking (`damage:`, issue 17 and 18) on its problem: the criterion
/// on the correspondence model, the no-fail zones, and the ModelChanges through which Verlet
/// (after its steps) and a load path (after its balances) drive it.
#include <memory>

#include "perinom/fracture/bond_breaking.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"
#include "perinom/solvers/model_changes.hpp"

namespace perinom {

class SceneBreaking {
 public:
  /// p.scene.damage must be set; p must outlive this object.
  explicit SceneBreaking(Problem& p);
  SceneBreaking(const SceneBreaking&) = delete;
  SceneBreaking& operator=(const SceneBreaking&) = delete;

  const ModelChanges& changes() const { return changes_; }
  /// The counts a run reports (SolveReport::changes): bonds broken, particles detached and,
  /// for the instability criterion, its s_hg_max and, in a Verlet run (`verlet`), the step
  /// it armed at (find() runs every `every` steps from step `every`).
  void report(SolveReport& r, bool verlet) const;

 private:
  Problem* p_;
  std::unique_ptr<BondBreaking> breaking_;
  ModelChanges changes_;
};

}  // namespace perinom
