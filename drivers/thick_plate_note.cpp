#include "thick_plate_note.hpp"

#include <algorithm>
#include <cstdio>

namespace perinom::cli {

std::string thick_plate_note(const Problem& p) {
  const Scene& s = p.scene;
  if (s.model.type != "thin_plate") return "";
  const double side = std::min(s.geometry.max[0] - s.geometry.min[0], s.geometry.max[1] - s.geometry.min[1]);
  const double t = s.geometry.thickness;
  if (!(t > kThickPlateRatio * side)) return "";
  char buf[600];
  std::snprintf(buf, sizeof buf,
                "geometry.thickness %g m is %.3g of the plate's shorter side (%g m): model.type thin_plate solves "
                "Kirchhoff's thin-plate theory, which neglects the transverse shear whose share of the deflection "
                "grows as (t / side)^2 (Reissner-Mindlin), so its deflection is a thin plate's and too small for "
                "this one; above a tenth a thick body wants a 3-D correspondence model",
                t, t / side, side);
  return buf;
}

}  // namespace perinom::cli
