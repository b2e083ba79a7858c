#pragma once
// What `perinom run` says about the supports: the pins of constraints: rigid_body, each
// support's reaction force and the equilibrium error of the final state.
#include <string>
#include <vector>

#include "perinom/io/json_writer.hpp"
#include "perinom/scene/problem.hpp"
#include "perinom/solvers/adr.hpp"

namespace perinom::cli {

/// Prints the rigid_body pins (particle, position, held components) and returns them for
/// summary.json: [{"particle": i, "position": [...], "components": ["x", ...]}, ...].
io::Json pin_results(const Problem& p);

/// The reactions at u under `loading` at factor s (Loading::reactions), printed with the
/// equilibrium error |sum of applied loads + sum of reactions| / |sum of applied loads| (when
/// the loads balance or there are none: over sum_k |f_k|, or the largest reaction). Sets
/// summary["reactions"] (NAME: [R per component], N) and summary["equilibrium"] (applied,
/// reactions: the sums; error; relative_to: which denominator).
/// A dynamic run (Verlet) gets the reactions only: inertia balances its loads too.
/// A distributed model's sums go over the ranks (every rank calls it). `carried` (N, 0: none)
/// is the largest reaction a load path had before its end (largest_reaction_carried): when
/// the end applies no load and its reactions are below it (a body broken apart, a path
/// unloaded to rest, whose reactions are rounding: the error read 1.000 on 1e-20 N), the error
/// is taken over the load the path carried instead.
/// `rounding` (N, 0: none): a solve that converged at its rounding floor passes its
/// stiffness force (SolveReport): the loads and reactions are rounding, and the error is taken
/// over the size of the forces the internal force sums instead.
void add_reaction_results(Model& model, const Loading& loading, double s, const std::vector<double>& u,
                          bool dynamic, io::Json& summary, double carried = 0.0, double rounding = 0.0);

/// The largest support reaction component of a load path's steps (the history's `.R`
/// columns, N); 0 without supports.
double largest_reaction_carried(const History& history);

/// For a static solve: solver.residual_force (N, |F| at the end), solver.stiffness_force (N,
/// the size of the forces the internal force sums) and solver.at_rounding_floor (converged
/// with |F| below their rounding while the relative residual was not below the tolerance).
void add_rounding_floor(const SolveReport& rep, io::Json& solver);

/// "residual R" for the closing line of a static run; for a solve that converged at its
/// rounding floor, also why R is large: the residual force against the rounding.
std::string residual_text(const SolveReport& rep);

}  // namespace perinom::cli
