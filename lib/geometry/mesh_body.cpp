#include "perinom/geometry/mesh_body.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "perinom/core/error.hpp"
#include "perinom/geometry/mesh_nodes.hpp"

namespace perinom {
namespace {

using Key = std::array<std::size_t, 4>;  // a face's node tags, ascending, padded with max

/// Local faces of the 3-D element types in gmsh's node order, each listed counterclockwise
/// seen from outside (the element's sign is checked anyway).
const std::vector<std::vector<int>>& local_faces(int type) {
  static const std::vector<std::vector<int>> tet{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  static const std::vector<std::vector<int>> hex{{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
  static const std::vector<std::vector<int>> prism{{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}};
  static const std::vector<std::vector<int>> pyramid{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return type == 4 ? tet : type == 5 ? hex : type == 6 ? prism : pyramid;
}

Key key_of(const GmshMesh& m, const std::size_t* nodes, int n) {
  Key k;
  k.fill(std::numeric_limits<std::size_t>::max());
  for (int v = 0; v < n; ++v) {  // insertion sort of at most 4 tags
    int w = v;
    for (; w > 0 && k[w - 1] > m.tag[nodes[v]]; --w) k[w] = k[w - 1];
    k[w] = m.tag[nodes[v]];
  }
  return k;
}

/// The groups (indices into boundary_groups) of each face that the mesh's elements of
/// dimension dim - 1 cover.
std::map<Key, std::vector<int>> face_groups(const GmshMesh& m, int dim, const std::vector<GmshGroup>& boundary_groups) {
  std::map<Key, std::vector<int>> out;
  for (std::size_t e = 0; e < m.elements(); ++e) {
    if (gmsh_element_shape(m.type[e]).first != dim - 1) continue;
    const auto it = m.entity_groups.find({m.dim[e], m.entity[e]});
    if (it == m.entity_groups.end()) continue;
    const Key k = key_of(m, m.node_index.data() + m.offsets[e], static_cast<int>(m.offsets[e + 1] - m.offsets[e]));
    auto& gs = out[k];
    for (const int tag : it->second)
      for (std::size_t g = 0; g < boundary_groups.size(); ++g)
        if (boundary_groups[g].tag == tag && std::find(gs.begin(), gs.end(), static_cast<int>(g)) == gs.end())
          gs.push_back(static_cast<int>(g));
  }
  return out;
}

struct Vec {
  double v[3] = {0, 0, 0};
  double& operator[](int a) { return v[a]; }
  double operator[](int a) const { return v[a]; }
};
Vec sub(const Vec& a, const Vec& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
Vec cross(const Vec& a, const Vec& b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }

/// One planar piece of an element's surface: vector area (outward) and centroid.
struct Piece {
  Vec area, centroid;
};

class Builder {
 public:
  Builder(const GmshMesh& m, int dim, double thickness) : m_(m), dim_(dim), thickness_(thickness) {
    for (const auto& g : m.groups)
      if (g.dim == dim - 1) boundary_groups_.push_back(g);
    std::sort(boundary_groups_.begin(), boundary_groups_.end(),
              [](const GmshGroup& a, const GmshGroup& b) { return a.tag < b.tag; });
    for (const auto& g : boundary_groups_) body_.groups.push_back({g.name, {}});
    body_.cloud.dim = dim;
    body_.facets.dim = dim;
  }

  Vec point(std::size_t node) const { return {{m_.x[3 * node], m_.x[3 * node + 1], m_.x[3 * node + 2]}}; }

  Body build() {
    // First: a 3-D mesh in a 2-D scene otherwise met "element 1 ... has zero area". Only the
    // nodes the body's elements use count: an unused construction point off the plane is no
    // part of it.
    const std::vector<std::size_t> nodes = used_nodes(m_, dim_);
    if (dim_ == 2) check_planar(m_, nodes);
    check_distinct_nodes(m_, nodes);
    for (std::size_t e = 0; e < m_.elements(); ++e)
      if (gmsh_element_shape(m_.type[e]).first == dim_) add_element(e);
    if (body_.cloud.size() == 0)
      throw InputError(std::string("the mesh holds no ") +
                       (dim_ == 2 ? "triangle or quadrangle (a 2-D scene's particles are its surface elements)"
                                  : "tetrahedron, hexahedron, prism or pyramid (a 3-D scene's particles are its volume elements)") +
                       "; did the .geo define a Physical " + (dim_ == 2 ? "Surface" : "Volume") +
                       "? gmsh then saves only the grouped elements");
    const auto groups = face_groups(m_, dim_, boundary_groups_);
    for (const auto& f : faces_) {
      if (f.second.size() > 2)
        throw InputError("a face of nodes " + std::to_string(f.first[0]) + ", " + std::to_string(f.first[1]) +
                         ", ... belongs to " + std::to_string(f.second.size()) + " elements (the mesh is not a manifold)");
      if (f.second.size() != 1) continue;
      const auto g = groups.find(f.first);
      add_facets(pieces_[f.second[0]], g == groups.end() ? std::vector<int>{} : g->second);
    }
    set_mean_size(body_, thickness_);
    body_.elements = body_.cloud.size();
    return std::move(body_);
  }

 private:
  struct FaceUse {
    std::size_t particle;
    std::vector<Piece> pieces;
  };

  void add_element(std::size_t e) {
    const std::size_t* nodes = m_.node_index.data() + m_.offsets[e];
    const int n = static_cast<int>(m_.offsets[e + 1] - m_.offsets[e]);
    Vec c;
    for (int v = 0; v < n; ++v)
      for (int a = 0; a < 3; ++a) c[a] += point(nodes[v])[a] / n;
    std::vector<std::pair<Key, std::vector<Piece>>> faces;
    double volume = 0.0;
    Vec moment;
    if (dim_ == 2) {
      // Polygon: signed area and centroid from the triangles (c, p_v, p_v+1); edges as faces.
      for (int v = 0; v < n; ++v) {
        const Vec a = point(nodes[v]), b = point(nodes[(v + 1) % n]);
        const double t = 0.5 * ((a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]));
        volume += t;
        for (int k = 0; k < 2; ++k) moment[k] += t * (a[k] + b[k] + c[k]) / 3.0;
        Piece p;
        p.area = {{b[1] - a[1], a[0] - b[0], 0.0}};  // length times the normal of a counterclockwise polygon
        for (int k = 0; k < 2; ++k) p.centroid[k] = 0.5 * (a[k] + b[k]);
        const std::size_t pair[2] = {nodes[v], nodes[(v + 1) % n]};
        faces.push_back({key_of(m_, pair, 2), {p}});
      }
    } else {
      for (const auto& face : local_faces(m_.type[e])) {
        const int fn = static_cast<int>(face.size());
        std::size_t fnodes[4];
        for (int v = 0; v < fn; ++v) fnodes[v] = nodes[face[v]];
        // Triangles of the face: a quadrangle is split along the diagonal through its node of
        // smallest tag, so the element on the other side splits it alike.
        int first = 0;
        for (int v = 1; v < fn; ++v)
          if (m_.tag[fnodes[v]] < m_.tag[fnodes[first]]) first = v;
        std::vector<Piece> pieces;
        for (int t = 0; t + 2 < fn; ++t) {
          const Vec a = point(fnodes[first]), b = point(fnodes[(first + t + 1) % fn]), d = point(fnodes[(first + t + 2) % fn]);
          Piece p;
          const Vec x = cross(sub(b, a), sub(d, a));
          for (int k = 0; k < 3; ++k) p.area[k] = 0.5 * x[k], p.centroid[k] = (a[k] + b[k] + d[k]) / 3.0;
          const double tet = dot(sub(a, c), cross(sub(b, c), sub(d, c))) / 6.0;
          volume += tet;
          for (int k = 0; k < 3; ++k) moment[k] += tet * (a[k] + b[k] + d[k] + c[k]) / 4.0;
          pieces.push_back(p);
        }
        faces.push_back({key_of(m_, fnodes, fn), pieces});
      }
    }
    if (!(std::abs(volume) > 0.0))
      throw InputError("element " + std::to_string(e + 1) + " of the file's element list (nodes " +
                       std::to_string(m_.tag[nodes[0]]) + ", " + std::to_string(m_.tag[nodes[1]]) +
                       ", ...) has zero " + (dim_ == 2 ? "area" : "volume"));
    const double sign = volume > 0.0 ? 1.0 : -1.0;  // elements numbered clockwise turn their faces inside out
    const std::size_t particle = body_.cloud.size();
    for (int a = 0; a < dim_; ++a) body_.cloud.x.push_back(moment[a] / volume);
    body_.cloud.volume.push_back(std::abs(volume) * (dim_ == 2 ? thickness_ : 1.0));
    for (auto& f : faces) {
      for (auto& p : f.second)
        for (int a = 0; a < 3; ++a) p.area[a] *= sign * (dim_ == 2 ? thickness_ : 1.0);
      faces_[f.first].push_back(pieces_.size());
      pieces_.push_back({particle, std::move(f.second)});
    }
  }

  void add_facets(const FaceUse& use, const std::vector<int>& groups) {
    std::vector<Piece> pieces = use.pieces;
    if (pieces.size() == 2) {
      const double a0 = norm(pieces[0].area), a1 = norm(pieces[1].area);
      Vec n0 = pieces[0].area, n1 = pieces[1].area;
      double gap = 0.0;
      for (int k = 0; k < 3; ++k) gap = std::max(gap, std::abs(n0[k] / a0 - n1[k] / a1));
      if (gap <= 1e-12) {  // a planar quadrangle: one facet
        Piece merged;
        for (int k = 0; k < 3; ++k) {
          merged.area[k] = n0[k] + n1[k];
          merged.centroid[k] = (a0 * pieces[0].centroid[k] + a1 * pieces[1].centroid[k]) / (a0 + a1);
        }
        pieces.assign(1, merged);
      }
    }
    for (const Piece& p : pieces) {
      const double A = norm(p.area);
      const std::size_t k = body_.facets.size();
      body_.facets.particle.push_back(static_cast<ParticleId>(use.particle));
      body_.facets.area.push_back(A);
      for (int a = 0; a < dim_; ++a) {
        body_.facets.normal.push_back(p.area[a] / A);
        body_.facets.centroid.push_back(p.centroid[a]);
      }
      body_.facets.side.push_back(groups.empty() ? -1 : 100 + groups[0]);
      for (const int g : groups) body_.groups[g].facets.push_back(k);
    }
  }

  const GmshMesh& m_;
  int dim_;
  double thickness_;
  std::vector<GmshGroup> boundary_groups_;
  Body body_;
  std::vector<FaceUse> pieces_;                      // every element face, in the order met
  std::map<Key, std::vector<std::size_t>> faces_;    // face nodes -> its uses (pieces_ indices)
};

}  // namespace

Body mesh_body(const GmshMesh& mesh, int dim, double thickness) { return Builder(mesh, dim, thickness).build(); }

}  // namespace perinom
