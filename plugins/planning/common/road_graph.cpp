#include "road_graph.hpp"

#include "io/bounded_read.hpp"
#include "io/whole_file.hpp"
#include "math/fnv1a.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace brickyard::planning {

double EdgeShape::d(double s) const {
  const double t = std::clamp((s - s_a) / (s_b - s_a), 0.0, 1.0);
  return d_a + (d_b - d_a) * t * t * t * (10 - 15 * t + 6 * t * t);
}
double EdgeShape::d1(double s) const {
  const double h = s_b - s_a, t = std::clamp((s - s_a) / h, 0.0, 1.0);
  return (d_b - d_a) * 30 * t * t * (1 - t) * (1 - t) / h;
}
double EdgeShape::d2(double s) const {
  const double h = s_b - s_a, t = std::clamp((s - s_a) / h, 0.0, 1.0);
  return (d_b - d_a) * 60 * t * (1 - t) * (1 - 2 * t) / (h * h);
}

double offset_curvature(double kr, double d, double d1, double d2) {
  const double q = 1 - kr * d, m = q * q + d1 * d1;
  return (q * d2 + kr * (q * q + 2 * d1 * d1)) / (m * std::sqrt(m));
}

void sample_shape(const RefLine& line, const EdgeShape& e, double step, std::vector<PathSample>& out) {
  const int n = std::max(1, static_cast<int>(std::ceil((e.s_b - e.s_a) / step - 1e-9)));
  for (int i = 0; i < n; ++i) {
    const double s = e.s_a + (e.s_b - e.s_a) * i / n, d = e.d(s);
    const Eigen::Vector2d p = line.point(s, d);
    out.push_back({p.x(), p.y(), s, d, offset_curvature(line.kappa(s), d, e.d1(s), e.d2(s))});
  }
}

namespace {
constexpr int kSpans[] = {1, 2, 3, 4, 6, 8};
constexpr int kSamples = 10;  // per edge, at the midpoints of equal steps in s
}  // namespace

void check_params(const RoadGraphParams& p) {
  auto in = [](const char* name, double v, double lo, double hi) {
    if (!(v >= lo && v <= hi)) {  // NaN fails too
      char buf[160];
      std::snprintf(buf, sizeof buf, "road graph: %s = %g is outside [%g, %g]", name, v, lo, hi);
      throw std::invalid_argument(buf);
    }
  };
  in("layer_spacing", p.layer_spacing, 1, 100);
  in("layer_spacing_turn", p.layer_spacing_turn, 1, 100);
  in("turn_curvature", p.turn_curvature, 0, 1);
  in("lateral_step", p.lateral_step, 0.1, 5);
  in("half_width", p.half_width, 0.1, 5);
  in("edge_margin", p.edge_margin, 0, 20);
  in("max_curvature", p.max_curvature, 0.001, 1);
  in("max_edge_length", p.max_edge_length, 5, 500);
}

namespace {

// Where the layers stand: the spacing of a stretch is the turn spacing when the line bends
// anywhere in it.
std::vector<double> layer_positions(const RefLine& line, const RoadGraphParams& p, double length) {
  std::vector<double> ls;
  for (double s = 0; s < length;) {
    ls.push_back(s);
    bool turn = false;
    for (double u = 0; u <= p.layer_spacing; u += 1.0) turn = turn || std::abs(line.kappa(s + u)) > p.turn_curvature;
    s += turn ? p.layer_spacing_turn : p.layer_spacing;
  }
  if (ls.size() > 1 && length - ls.back() < 0.5 * p.layer_spacing_turn) ls.pop_back();  // no sliver before the start
  if (ls.size() < 3) throw std::invalid_argument("road graph: the line is shorter than three layers");
  return ls;
}

// The layers with their nodes, each node's layer, and the band of d each layer's nodes may take
// (the track's edges less half the car's width and the margin).
struct LayerNodes {
  std::vector<RoadGraph::Layer> layers;
  std::vector<std::uint32_t> node_layer;
  std::vector<double> lo, hi;
};

LayerNodes layer_nodes(const std::vector<double>& ls, const TrackRoom& room, const RoadGraphParams& p) {
  const int nl = static_cast<int>(ls.size());
  LayerNodes out{{}, {}, std::vector<double>(nl), std::vector<double>(nl)};
  for (int i = 0; i < nl; ++i) {
    const auto [dr, dl] = room(ls[i]);
    if (!(std::abs(dr) < 1000 && std::abs(dl) < 1000)) {  // NaN too: it must not reach an int cast
      char buf[160];
      std::snprintf(buf, sizeof buf, "road graph: at s = %.1f m the track's edges are not usable (d = %g and %g m)", ls[i], dr, dl);
      throw std::invalid_argument(buf);
    }
    out.lo[i] = dr + p.half_width + p.edge_margin;
    out.hi[i] = dl - p.half_width - p.edge_margin;
    RoadGraph::Layer L;
    L.s = ls[i];
    L.k0 = static_cast<std::int32_t>(std::ceil(out.lo[i] / p.lateral_step - 1e-9));
    const auto k1 = static_cast<std::int32_t>(std::floor(out.hi[i] / p.lateral_step + 1e-9));
    if (k1 < L.k0) {
      char buf[200];
      std::snprintf(buf, sizeof buf, "road graph: at s = %.1f m the track leaves no room for the car (edges at d = %.2f and %.2f m)",
                    ls[i], dr, dl);
      throw std::invalid_argument(buf);
    }
    L.count = static_cast<std::uint32_t>(k1 - L.k0 + 1);
    L.first_node = static_cast<std::uint32_t>(out.node_layer.size());
    out.layers.push_back(L);
    out.node_layer.insert(out.node_layer.end(), L.count, static_cast<std::uint32_t>(i));
  }
  return out;
}

// The edges of one layer's nodes: per node its first edge, within `edges`.
struct LayerEdges {
  std::vector<std::uint32_t> first;
  std::vector<RoadGraph::Edge> edges;
};

// What the edges are built from.
struct EdgeSource {
  const RefLine& line;
  const RoadGraphParams& p;
  const LayerNodes& nodes;
  double length;
};

// Whether the edge from layer a over `span` layers stays inside the track at every layer it passes.
bool inside_track(const EdgeSource& src, const EdgeShape& e, int a, int span) {
  const auto& layers = src.nodes.layers;
  const int nl = static_cast<int>(layers.size());
  bool inside = true;
  for (int m = 1; m < span && inside; ++m) {
    const int c = (a + m) % nl;
    double sc = layers[c].s - layers[a].s;
    if (sc < 0) sc += src.length;
    const double dc = e.d(sc);
    inside = dc >= src.nodes.lo[c] - 1e-9 && dc <= src.nodes.hi[c] + 1e-9;
  }
  return inside;
}

// The edge's length, ∫κ² dl, ∫|d| ds and largest |κ| from samples at the midpoints of equal
// steps in s, into E; false: sharper than max_curvature (and not along the line).
bool measure_edge(const EdgeSource& src, const EdgeShape& e, double s_a, double h, bool along, RoadGraph::Edge& E) {
  double len = 0, curv = 0, dev = 0, kmax = 0;
  const double ds = h / kSamples;
  for (int k = 0; k < kSamples; ++k) {
    const double s = (k + 0.5) * ds;
    const double d = e.d(s), d1 = e.d1(s), kr = src.line.kappa(s_a + s);
    const double q = 1 - kr * d, dl = std::sqrt(q * q + d1 * d1) * ds;
    const double kappa = offset_curvature(kr, d, d1, e.d2(s));
    len += dl;
    curv += kappa * kappa * dl;
    dev += std::abs(d) * ds;
    kmax = std::max(kmax, std::abs(kappa));
  }
  if (!along && kmax > src.p.max_curvature) return false;
  E.length = static_cast<float>(len);
  E.curvature = static_cast<float>(curv);
  E.deviation = static_cast<float>(dev);
  E.max_kappa = static_cast<float>(kmax);
  return true;
}

// Layer a's edges on their own: a pure function of the layers.
LayerEdges layer_edges(const EdgeSource& src, int a) {
  const auto& layers = src.nodes.layers;
  const int nl = static_cast<int>(layers.size());
  const RoadGraphParams& p = src.p;
  const RoadGraph::Layer& A = layers[a];
  LayerEdges out;
  for (std::uint32_t i = 0; i < A.count; ++i) {
    out.first.push_back(static_cast<std::uint32_t>(out.edges.size()));
    const double da = (A.k0 + static_cast<std::int32_t>(i)) * p.lateral_step;
    for (int span : kSpans) {
      if (span >= nl) break;
      const int b = (a + span) % nl;
      const RoadGraph::Layer& B = layers[b];
      double h = B.s - A.s;
      if (h <= 0) h += src.length;
      if (h > p.max_edge_length && span > 1) break;
      for (std::uint32_t j = 0; j < B.count; ++j) {
        const double db = (B.k0 + static_cast<std::int32_t>(j)) * p.lateral_step;
        const bool along = std::abs(db - da) < 1e-9;
        if (along && span > 1) continue;  // the chain of span-1 edges is the same path
        const EdgeShape e{0, da, h, db};
        if (!inside_track(src, e, a, span)) continue;
        RoadGraph::Edge E;
        E.to = B.first_node + j;
        if (measure_edge(src, e, A.s, h, along, E)) out.edges.push_back(E);
      }
    }
  }
  return out;
}

// Every layer's edges, on two threads; each layer's come out the same whatever the threads did first.
std::vector<LayerEdges> all_layer_edges(const EdgeSource& src) {
  const int nl = static_cast<int>(src.nodes.layers.size());
  std::vector<LayerEdges> per_layer(nl);
  std::atomic<int> next{0};
  auto worker = [&] {
    for (int a; (a = next++) < nl;) per_layer[a] = layer_edges(src, a);
  };
  std::thread second(worker);
  worker();
  second.join();
  return per_layer;
}

}  // namespace

RoadGraph RoadGraph::build(const RefLine& line, const TrackRoom& room, const RoadGraphParams& p,
                           std::uint64_t digest) {
  check_params(p);
  RoadGraph g;
  g.p_ = p;
  g.digest_ = digest;
  g.length_ = line.length();
  const LayerNodes nodes = layer_nodes(layer_positions(line, p, g.length_), room, p);
  g.layers_ = nodes.layers;
  g.node_layer_ = nodes.node_layer;
  // Edges: each layer's on its own, then joined in layer order, so the graph is the same
  // whatever the threads did first.
  std::vector<LayerEdges> per_layer = all_layer_edges(EdgeSource{line, p, nodes, g.length_});
  std::size_t total = 0;
  for (const auto& le : per_layer) total += le.edges.size();
  g.first_edge_.reserve(g.node_layer_.size() + 1);
  g.edges_.reserve(total);
  for (auto& le : per_layer) {
    const auto base = static_cast<std::uint32_t>(g.edges_.size());
    for (std::uint32_t f : le.first) g.first_edge_.push_back(base + f);
    g.edges_.insert(g.edges_.end(), le.edges.begin(), le.edges.end());
    le = LayerEdges{};  // freed as it goes: the graph may be a million edges
  }
  g.first_edge_.push_back(static_cast<std::uint32_t>(g.edges_.size()));
  return g;
}

int RoadGraph::layer_at_or_after(double s) const {
  s = std::fmod(s, length_);
  if (s < 0) s += length_;
  auto it = std::lower_bound(layers_.begin(), layers_.end(), s, [](const Layer& l, double v) { return l.s < v; });
  return it == layers_.end() ? 0 : static_cast<int>(it - layers_.begin());
}

std::uint32_t RoadGraph::nearest_node(int layer, double d) const {
  const Layer& L = layers_[layer];
  const double k = std::round(d / p_.lateral_step) - L.k0;
  const double i = std::clamp(k, 0.0, static_cast<double>(L.count - 1));
  return L.first_node + static_cast<std::uint32_t>(i);
}

// File: "BYRG", format version, the parameters, the source digest, the line's length, then the
// layers, the first-edge index of every node and the edges, each array preceded by its count;
// last, an FNV-1a digest of every byte before it (version 2: a bit flipped anywhere is refused,
// where version 1 loaded 14 of 53 such files). Little-endian, as written by this machine; the
// loader checks the digest, then every count and index.
namespace {
constexpr char kMagic[4] = {'B', 'Y', 'R', 'G'};
constexpr std::uint32_t kVersion = 2;
constexpr std::uint64_t kMaxFileBytes = 1ull << 30;  // a road graph of a 20 km track is tens of MB

template <class T>
void put(std::ostream& f, const T& v) { f.write(reinterpret_cast<const char*>(&v), sizeof(T)); }
template <class T>
void put_vec(std::ostream& f, const std::vector<T>& v) {
  put(f, static_cast<std::uint64_t>(v.size()));
  f.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}
}  // namespace

void RoadGraph::save(const std::string& path) const {
  std::ostringstream o(std::ios::binary);
  o.write(kMagic, 4);
  put(o, kVersion);
  put(o, p_);
  put(o, digest_);
  put(o, length_);
  put_vec(o, layers_);
  put_vec(o, first_edge_);
  put_vec(o, edges_);
  std::string bytes = std::move(o).str();
  const std::uint64_t sum = math::fnv1a(bytes);
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  io::write_whole_file(path, bytes);  // whole or not at all
}

namespace {

std::runtime_error unusable(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": not a usable road graph (" + what + ")");
}

std::string read_graph_file(const std::string& path) {
  // A FIFO or a device refused before the stream opens it (a FIFO's open waits for a writer).
  if (std::string error; !io::is_regular_readable(path, error)) throw std::runtime_error(error);
  std::string bytes;
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error(path + ": cannot open");
  const std::streamoff size = in.tellg();
  if (size < 0) throw unusable(path, "not a regular file");
  if (static_cast<std::uint64_t>(size) > kMaxFileBytes) throw unusable(path, std::to_string(size) + " bytes, more than a road graph holds");
  bytes.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  in.read(bytes.data(), size);
  if (!in) throw unusable(path, "cannot be read");
  return bytes;
}

// The magic, the format version and the digest of every byte before it.
void check_header_and_digest(const std::string& path, const std::string& bytes) {
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, 4) != 0) throw unusable(path, "no BYRG header");
  std::uint32_t version = 0;
  std::memcpy(&version, bytes.data() + 4, sizeof version);
  if (version != kVersion)
    throw unusable(path, "format version " + std::to_string(version) + ", this build reads " + std::to_string(kVersion) +
                             ": rebuild it with brickyard-plan graph");
  if (bytes.size() < 16) throw unusable(path, "truncated at digest");
  std::uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - sizeof sum, sizeof sum);
  if (math::fnv1a(std::string_view(bytes.data(), bytes.size() - sizeof sum)) != sum)
    throw unusable(path, "its digest does not match its bytes: damaged or cut short");
}

// The file's fields after the header, in order.
class GraphReader {
 public:
  GraphReader(std::string bytes, const std::string& path) : f_(std::move(bytes), std::ios::binary), path_(path) { f_.seekg(8); }
  template <class T>
  void get(T& v, const char* what) {
    f_.read(reinterpret_cast<char*>(&v), sizeof(v));
    if (!f_) throw unusable(path_, std::string("truncated at ") + what);
  }
  template <class T>
  void get_vec(std::vector<T>& v, const char* what, std::uint64_t limit) {
    std::uint64_t n = 0;
    get(n, what);
    if (n > limit) throw unusable(path_, std::string(what) + " count " + std::to_string(n) + " is implausible");
    v.resize(n);
    f_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(v[0])));
    if (!f_) throw unusable(path_, std::string("truncated in ") + what);
  }
  bool at_end() { return f_.peek() == std::char_traits<char>::eof(); }

 private:
  std::istringstream f_;
  const std::string& path_;
};

// Layers in order, their nodes contiguous and within a kilometre of the line; counts checked in
// 64 bits before anything is allocated for them. Returns the number of nodes.
std::uint64_t checked_node_count(const std::string& path, const std::vector<RoadGraph::Layer>& layers, double length,
                                 double lateral_step) {
  std::uint64_t nodes = 0;
  const double k_max = 1000 / lateral_step;
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const RoadGraph::Layer& L = layers[i];
    if (L.first_node != nodes || L.count == 0 || !(L.s >= 0 && L.s < length) || (i > 0 && L.s <= layers[i - 1].s) ||
        std::abs(static_cast<double>(L.k0)) > k_max || L.count > 2 * k_max + 1)
      throw unusable(path, "layer " + std::to_string(i) + " is out of order or out of bounds");
    nodes += L.count;
  }
  return nodes;
}

// Every node's edge range within the edges, before any edge is read (a range past them, found by
// fuzzing, read beyond the array).
void check_edge_ranges(const std::string& path, const std::vector<std::uint32_t>& first_edge) {
  for (std::size_t n = 0; n + 1 < first_edge.size(); ++n)
    if (first_edge[n] > first_edge[n + 1]) throw unusable(path, "edge ranges out of order at node " + std::to_string(n));
}

// Edges: in range, finite, non-negative, and forward by 1 to 8 layers — the search is a DAG pass
// that a backward edge would turn into a cycle.
void check_edges(const std::string& path, const std::vector<std::uint32_t>& first_edge, const std::vector<RoadGraph::Edge>& edges,
                 const std::vector<std::uint32_t>& node_layer, std::uint64_t nodes, std::uint32_t nl) {
  for (std::size_t n = 0; n + 1 < first_edge.size(); ++n) {
    for (std::uint32_t k = first_edge[n]; k < first_edge[n + 1]; ++k) {
      const RoadGraph::Edge& e = edges[k];
      if (e.to >= nodes) throw unusable(path, "edge " + std::to_string(k) + " leads past the last node");
      const std::uint32_t ahead = (node_layer[e.to] + nl - node_layer[n]) % nl;
      if (ahead < 1 || ahead > 8) throw unusable(path, "edge " + std::to_string(k) + " does not lead 1 to 8 layers forward");
      for (float v : {e.length, e.curvature, e.deviation, e.max_kappa})
        if (!(v >= 0 && v < 1e9)) throw unusable(path, "edge " + std::to_string(k) + " has a negative or non-finite cost");
      if (!(e.length > 0)) throw unusable(path, "edge " + std::to_string(k) + " has no length");
    }
  }
}

}  // namespace

RoadGraph RoadGraph::load(const std::string& path) {
  std::string bytes = read_graph_file(path);
  check_header_and_digest(path, bytes);
  GraphReader f(std::move(bytes), path);
  RoadGraph g;
  f.get(g.p_, "parameters");
  try {
    check_params(g.p_);
  } catch (const std::invalid_argument& e) {
    throw unusable(path, e.what());
  }
  f.get(g.digest_, "digest");
  f.get(g.length_, "length");
  if (!(g.length_ > 0 && g.length_ < 1e6)) throw unusable(path, "implausible line length");
  f.get_vec(g.layers_, "layers", 1u << 24);
  f.get_vec(g.first_edge_, "nodes", 1u << 26);
  f.get_vec(g.edges_, "edges", 1u << 28);
  std::uint64_t trailing = 0;
  f.get(trailing, "digest");
  if (!f.at_end()) throw unusable(path, "trailing bytes");
  // Consistency: layers in order and their nodes contiguous; edge ranges and targets in bounds.
  const std::uint64_t nodes = checked_node_count(path, g.layers_, g.length_, g.p_.lateral_step);
  if (g.layers_.size() < 3 || g.first_edge_.size() != nodes + 1 || g.first_edge_.back() != g.edges_.size())
    throw unusable(path, "node and edge counts disagree");
  check_edge_ranges(path, g.first_edge_);
  g.node_layer_.reserve(nodes);
  for (std::size_t i = 0; i < g.layers_.size(); ++i)
    g.node_layer_.insert(g.node_layer_.end(), g.layers_[i].count, static_cast<std::uint32_t>(i));
  check_edges(path, g.first_edge_, g.edges_, g.node_layer_, nodes, static_cast<std::uint32_t>(g.layers_.size()));
  return g;
}

}  // namespace brickyard::planning
