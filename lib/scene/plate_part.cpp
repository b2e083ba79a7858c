// A distributed rank's thin plate (issue 19): the part's nodes and their mirrors, fitted at
// the owned and near nodes.
#include "perinom/scene/plate_part.hpp"

#include <stdexcept>

namespace perinom {

std::unique_ptr<ThinPlateModel> plate_part_model(const Scene& s, const PlateFrame& frame, const LocalPart& part,
                                                 PlateCloud plate, const Families& families) {
  if (s.discretization.horizon_neighbors > 0)
    throw std::logic_error("plate_part_model: radius families only (k-nearest ones are searched on the whole plate)");
  ThinPlateOptions opt = frame.options;
  opt.fitted_rows = part.owned + part.near;
  return plate_model(s, std::move(plate), families, opt);
}

}  // namespace perinom
