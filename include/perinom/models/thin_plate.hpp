#pragma once
/// @file The nonlocal Kirchhoff thin plate (THEORY sec. 7; seed 002 sec. 3.2, 6.2).
#include <cstdint>
#include <functional>
#include <optional>
#include <utility>

#include "perinom/geometry/plate_cloud.hpp"
#include "perinom/models/local_model.hpp"
#include "perinom/neighbors/families.hpp"
#include "perinom/operators/influence.hpp"
#include "perinom/operators/nonlocal_operator.hpp"
#include "perinom/operators/stabilization.hpp"

namespace perinom {

struct ThinPlateOptions {
  double E = 0.0;          ///< Young's modulus (Pa)
  double nu = 0.0;         ///< Poisson's ratio
  double thickness = 0.0;  ///< t (m)
  double density = 0.0;    ///< rho (kg/m^3)
  Influence influence = Influence::inverse_square;
  double stabilization = 0.5;  ///< C_hg of the operator energy (operators/stabilization.hpp); 0: none
  /// How each edge is held (0 xmin, 1 xmax, 2 ymin, 3 ymax), as the PlateCloud's ghosts were
  /// made; for the plan only (the ghosts and the Loading carry the conditions).
  PlateEdges edges{EdgeSupport::free, EdgeSupport::free, EdgeSupport::free, EdgeSupport::free};
  /// A distributed rank's local plate (plate_part): the physical nodes from this one on (its
  /// far ghosts, whose families the part truncates) are not fitted and carry no energy; they
  /// and the mirror ghosts only lend their values. Every node by default.
  std::size_t fitted_rows = SIZE_MAX;
};

/// Deflection w (m), one unknown per physical node of a PlateCloud. With kappa_i = (Hess w)_i
/// stored as (xx, xy, yy) and the bending moments M = D0 (nu tr(kappa) I + (1 - nu) kappa)
/// (N m / m), D0 = E t^3 / (12 (1 - nu^2)):
///   W(w) = sum_i A_i 1/2 M_i : kappa_i + W_s(w),    f = dW/dw = H^T (A . (Mxx, 2 Mxy, Myy)) + S w,
/// A_i the node's quadrature area, W_s the operator-energy stabilization. The ghosts of
/// the supported edges enter the fits with w_ghost = sign w_image; their forces are folded
/// onto their images (f_image += sign f_ghost), so W is minimised over the physical nodes
/// alone and the stiffness stays symmetric. Loads (pressure q: q A_i) and the edge
/// conditions w = 0 come from a Loading. Lumped mass rho t A_i.
/// Over MPI ranks (issue 19) each rank holds the plate of its local part (sub_plate: its
/// nodes, then the ghosts mirroring them): a centre whose Hessian reaches an owned node or
/// one of its mirrors lies within one horizon of that node (a mirror is no nearer to a centre
/// than its image), so the owned and near nodes' fits give the owned force exactly.
class ThinPlateModel : public LocalModel {
 public:
  /// Assembles the second-order operator (gradient and Hessian) on plate.cloud and the
  /// stabilization. Throws InputError naming a particle whose fit is singular, or an option
  /// out of its range (E, thickness, density positive and finite, -1 < nu < 1/2,
  /// stabilization >= 0).
  ThinPlateModel(PlateCloud plate, const Families& families, const ThinPlateOptions& options);
  ThinPlateModel(const ThinPlateModel&) = delete;
  ThinPlateModel& operator=(const ThinPlateModel&) = delete;

  std::size_t particles() const override { return plate_.physical; }
  int dofs_per_particle() const override { return 1; }
  void internal_force(const double* w, double* f) override;
  double energy(const double* w) override;
  std::vector<double> lumped_mass() const override;
  std::vector<double> stiffness_row_sums() const override;
  std::vector<std::pair<std::string, std::size_t>> memory() const override;

  /// Visits every row of the stiffness K = dF/dw over the physical nodes (ghosts folded),
  /// visit(row, cols, values) with cols sorted; called concurrently for distinct rows.
  void visit_tangent_rows(const TangentRowVisitor& visit) const override;
  /// The listed physical nodes' rows (sorted, distinct), and their stiffness row sums.
  void visit_tangent_rows(const std::vector<ParticleId>& rows, const TangentRowVisitor& visit) const override;
  std::vector<double> stiffness_row_sums(const std::vector<ParticleId>& rows) const override;
  /// A rank's local plate: Hessians and moments at the first `evaluated` nodes (at most
  /// ThinPlateOptions::fitted_rows); energy() is then the first `written` nodes' share,
  /// 1/2 w . f over them (W is quadratic in w).
  void limit_rows(std::size_t evaluated, std::size_t written) override;
  /// The plate is linear: K does not depend on w, so there is nothing to prepare.
  void prepare_tangent(const double*) override {}

  /// kappa = Hess w (N x 3: xx, xy, yy; 1/m) and M (N x 3: xx, xy, yy; N m / m) per physical node.
  void curvature(const double* w, double* kappa) const;
  void moments(const double* w, double* M) const;

  /// D0 = E t^3 / (12 (1 - nu^2)) (N m).
  double rigidity() const { return D0_; }
  const PlateCloud& plate() const { return plate_; }
  const NonlocalOperator& op() const { return op_; }

  // What drivers ask of any model (thin_plate_output.cpp): the fields deflection (m),
  // displacement (0, 0, w) for ParaView's Warp By Vector, curvature (1/m) and moment
  // (N m / m) as 3 x 3 tensors (zz, xz, yz zero), volume (quadrature area times thickness).
  std::vector<OutputField> output_fields(const double* w, bool probe_fields = false,
                                         bool gradients = false) const override;
  std::vector<double> stress_measure(const double* w) const override;
  std::vector<PlanLine> plan() const override;
  std::vector<std::string> not_assembled() const override;
  /// A plate takes no `fix`: its supports are edges, simply supported or clamped.
  std::string support_advice() const override;

 private:
  void extend(const double* w, std::vector<double>& ext) const;
  void derivatives(const double* w);  // ext_, grad_, hess_ at w
  void moment(const double* kappa, double* M) const;
  RowFill row_fill() const;  // the stiffness rows, ghosts folded
  PlateCloud plate_;
  ThinPlateOptions opt_;
  double D0_;
  NonlocalOperator op_;
  std::optional<Stabilization> S_;
  std::vector<Offset> ghost_off_;         // per physical node: its ghosts (CSR)
  std::vector<ParticleId> ghost_list_;
  std::vector<double> ext_, grad_, hess_, Q_, fe_;  // workspaces over all nodes
  std::vector<double> share_;  // energy()'s force on a rank (limit_rows): the physical nodes'
  std::size_t evaluated_ = SIZE_MAX, written_ = SIZE_MAX;  // limit_rows
};

}  // namespace perinom
