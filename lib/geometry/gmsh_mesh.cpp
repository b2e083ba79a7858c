#include "perinom/geometry/gmsh_mesh.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "perinom/core/error.hpp"

namespace perinom {
namespace {

/// The file as whitespace-separated tokens (a quoted name is one token), with line numbers.
class Tokens {
 public:
  explicit Tokens(std::string text) : text_(std::move(text)) {}

  bool done() {
    skip_space();
    return pos_ >= text_.size();
  }
  std::string next(const char* what) {
    skip_space();
    if (pos_ >= text_.size()) fail(std::string("the file ends where ") + what + " should be");
    const std::size_t start = pos_;
    if (text_[pos_] == '"') {
      const std::size_t end = text_.find('"', pos_ + 1);
      if (end == std::string::npos) fail("a quoted name is not closed");
      pos_ = end + 1;
      return text_.substr(start + 1, end - start - 1);
    }
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  long long integer(const char* what) {
    const std::string t = next(what);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (end == t.c_str() || *end != '\0' || errno) fail(std::string(what) + " must be a whole number, not '" + t + "'");
    return v;
  }
  double number(const char* what) {
    const std::string t = next(what);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0') fail(std::string(what) + " must be a number, not '" + t + "'");
    return v;
  }
  /// Skips the rest of the current line (optional trailing values such as parametric ones).
  void skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("line " + std::to_string(line_) + ": " + what);
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  std::string text_;
  std::size_t pos_ = 0;
  long line_ = 1;
};

void expect(Tokens& t, const std::string& word) {
  const std::string got = t.next(word.c_str());
  if (got != word) t.fail("expected " + word + ", found '" + got + "'");
}

void read_format(Tokens& t) {
  const std::string version = t.next("the format version");
  const long long binary = t.integer("the file type");
  t.integer("the data size");
  if (version.rfind("4.1", 0) != 0)
    t.fail("mesh format " + version + "; perinom reads format 4.1 (save with gmsh -format msh41)");
  if (binary != 0) t.fail("a binary mesh; perinom reads the ASCII form (Mesh.Binary = 0)");
  expect(t, "$EndMeshFormat");
}

void read_names(Tokens& t, GmshMesh& m) {
  const long long n = t.integer("the number of physical names");
  for (long long k = 0; k < n; ++k) {
    GmshGroup g;
    g.dim = static_cast<int>(t.integer("a physical group's dimension"));
    g.tag = static_cast<int>(t.integer("a physical group's tag"));
    g.name = t.next("a physical group's name");
    m.groups.push_back(g);
  }
  expect(t, "$EndPhysicalNames");
}

void read_entities(Tokens& t, GmshMesh& m) {
  long long count[4];
  for (auto& c : count) c = t.integer("the number of entities");
  for (int d = 0; d < 4; ++d)
    for (long long k = 0; k < count[d]; ++k) {
      const int tag = static_cast<int>(t.integer("an entity tag"));
      for (int c = 0; c < (d == 0 ? 3 : 6); ++c) t.number("an entity's bounding box");
      const long long physicals = t.integer("an entity's number of physical tags");
      std::vector<int> tags;
      for (long long p = 0; p < physicals; ++p) tags.push_back(static_cast<int>(t.integer("a physical tag")));
      if (!tags.empty()) m.entity_groups[{d, tag}] = tags;
      if (d == 0) continue;
      const long long bounding = t.integer("an entity's number of bounding entities");
      for (long long b = 0; b < bounding; ++b) t.integer("a bounding entity");
    }
  expect(t, "$EndEntities");
}

void read_nodes(Tokens& t, GmshMesh& m, std::unordered_map<long long, std::size_t>& index) {
  const long long blocks = t.integer("the number of node blocks");
  const long long total = t.integer("the number of nodes");
  t.integer("the smallest node tag");
  t.integer("the largest node tag");
  m.tag.reserve(total);
  m.x.reserve(3 * total);
  for (long long b = 0; b < blocks; ++b) {
    const long long entity_dim = t.integer("a node block's entity dimension");
    t.integer("a node block's entity tag");
    const long long parametric = t.integer("a node block's parametric flag");
    const long long n = t.integer("a node block's size");
    for (long long k = 0; k < n; ++k) {
      const long long tag = t.integer("a node tag");
      if (!index.emplace(tag, m.tag.size()).second) t.fail("node " + std::to_string(tag) + " is defined twice");
      m.tag.push_back(static_cast<std::size_t>(tag));
    }
    for (long long k = 0; k < n; ++k) {
      for (int a = 0; a < 3; ++a) m.x.push_back(t.number("a node coordinate"));
      if (parametric)
        for (long long p = 0; p < entity_dim; ++p) t.number("a parametric coordinate");
    }
  }
  if (static_cast<long long>(m.tag.size()) != total)
    t.fail("the node blocks hold " + std::to_string(m.tag.size()) + " nodes, the header says " + std::to_string(total));
  expect(t, "$EndNodes");
}

void read_elements(Tokens& t, GmshMesh& m, const std::unordered_map<long long, std::size_t>& index) {
  const long long blocks = t.integer("the number of element blocks");
  t.integer("the number of elements");
  t.integer("the smallest element tag");
  t.integer("the largest element tag");
  for (long long b = 0; b < blocks; ++b) {
    const int entity_dim = static_cast<int>(t.integer("an element block's entity dimension"));
    const int entity = static_cast<int>(t.integer("an element block's entity tag"));
    const int type = static_cast<int>(t.integer("an element type"));
    const long long n = t.integer("an element block's size");
    const int nodes = gmsh_element_shape(type).second;
    if (nodes == 0)
      t.fail("gmsh element type " + std::to_string(type) +
             " is not read: perinom takes first-order points, lines, triangles, quadrangles, "
             "tetrahedra, hexahedra, prisms and pyramids (mesh with Mesh.ElementOrder = 1)");
    for (long long k = 0; k < n; ++k) {
      const long long element = t.integer("an element tag");
      const std::size_t first = m.node_index.size();
      for (int v = 0; v < nodes; ++v) {
        const long long tag = t.integer("an element's node tag");
        const auto it = index.find(tag);
        if (it == index.end()) t.fail("an element refers to node " + std::to_string(tag) + ", which is not defined");
        // A collapsed element (a quadrangle 1 2 13 13) has a zero-length edge: a 2-D body ran
        // 16% off the patch test with a facet of zero length, a 3-D one ended in NaN stresses.
        for (std::size_t w = first; w < m.node_index.size(); ++w)
          if (m.node_index[w] == it->second)
            t.fail("element " + std::to_string(element) + " lists node " + std::to_string(tag) +
                   " twice: a collapsed element is refused; give it as the element of fewer nodes it "
                   "has become (a triangle, a prism, a pyramid) or remesh");
        m.node_index.push_back(it->second);
      }
      m.type.push_back(type);
      m.dim.push_back(entity_dim);
      m.entity.push_back(entity);
      m.offsets.push_back(m.node_index.size());
    }
  }
  expect(t, "$EndElements");
}

}  // namespace

std::pair<int, int> gmsh_element_shape(int type) {
  switch (type) {
    case 15: return {0, 1};
    case 1: return {1, 2};
    case 2: return {2, 3};
    case 3: return {2, 4};
    case 4: return {3, 4};
    case 5: return {3, 8};
    case 6: return {3, 6};
    case 7: return {3, 5};
    default: return {-1, 0};
  }
}

GmshMesh read_gmsh(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open the mesh file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError("cannot read the mesh file");
  Tokens t(buffer.str());
  GmshMesh m;
  std::unordered_map<long long, std::size_t> index;
  bool format = false, nodes = false, elements = false;
  while (!t.done()) {
    const std::string section = t.next("a section");
    if (section.empty() || section[0] != '$') t.fail("expected a section such as $Nodes, found '" + section + "'");
    if (section != "$MeshFormat" && !format) t.fail("a .msh file starts with $MeshFormat");
    if (section == "$MeshFormat") read_format(t), format = true;
    else if (section == "$PhysicalNames") read_names(t, m);
    else if (section == "$Entities") read_entities(t, m);
    else if (section == "$PartitionedEntities") t.fail("a partitioned mesh; save it unpartitioned");
    else if (section == "$Nodes") read_nodes(t, m, index), nodes = true;
    else if (section == "$Elements") {
      if (!nodes) t.fail("$Elements comes before $Nodes");
      read_elements(t, m, index), elements = true;
    } else {
      // Sections perinom does not use ($Periodic, $NodeData, ...): skipped whole.
      const std::string end = "$End" + section.substr(1);
      while (t.next(end.c_str()) != end) {
      }
    }
  }
  if (!format) throw InputError("the file is empty; a .msh file starts with $MeshFormat");
  if (!nodes || !elements) throw InputError("the file has no $Nodes or no $Elements section");
  // A group the file leaves unnamed is named by its tag.
  for (const auto& e : m.entity_groups)
    for (const int tag : e.second) {
      bool known = false;
      for (const auto& g : m.groups) known = known || (g.dim == e.first.first && g.tag == tag);
      if (!known) m.groups.push_back({e.first.first, tag, std::to_string(tag)});
    }
  return m;
}

}  // namespace perinom
