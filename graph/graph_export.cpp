// GraphViz DOT and GraphML export of a frame range (Boost's writers).
#include <charconv>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/graphml.hpp>
#include <boost/graph/graphviz.hpp>
#include <boost/property_map/dynamic_property_map.hpp>
#include <boost/smart_ptr/make_shared.hpp>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "graph/graph_io.h"

namespace gmg {
namespace {

// Boost.Graph's writers take one of its graphs: the exported part is copied into its compressed
// sparse row graph (vertex i = frame from + i), the edges in the storage's order, so that edge
// index i is weight[i]'s.
using ExportGraph = boost::compressed_sparse_row_graph<boost::directedS, NodeInfo, boost::no_property,
                                                       boost::no_property, GraphVertex, std::uint32_t>;
struct Part {
  ExportGraph graph;
  std::vector<double> weight;
};

// The subgraph of frames [from, to): its edges inside the range.
Part subgraph(const MotionGraph& g, int from, int to) {
  if (from < 0 || to > g.frame_count() || from >= to)
    throw Error("frame range " + std::to_string(from) + ":" + std::to_string(to) +
                " is outside the graph's 0:" + std::to_string(g.frame_count()));
  std::vector<std::pair<GraphVertex, GraphVertex>> edges;
  Part part;
  for (int f = from; f < to; ++f)
    for (const GraphEdge e : g.graph.out_edges(static_cast<GraphVertex>(f))) {
      const int b = static_cast<int>(g.graph.target(e));
      if (b >= from && b < to) {
        edges.emplace_back(static_cast<GraphVertex>(f - from), static_cast<GraphVertex>(b - from));
        part.weight.push_back(g.weight(e));
      }
    }
  part.graph = ExportGraph(boost::edges_are_sorted, edges.begin(), edges.end(), static_cast<std::size_t>(to - from));
  for (int f = from; f < to; ++f) part.graph[static_cast<std::size_t>(f - from)] = g.node(f);
  return part;
}

// The edges' weights as the GraphML writer asks for them. Boost's own adaptor prints a double
// through a fresh stream, with six significant digits; this map prints each weight in the shortest
// form that reads back as the same double (std::to_chars), and still declares it a double, so the
// file's key says attr.type="double" and a reader parses a number.
class ExactWeights : public boost::dynamic_property_map {
 public:
  explicit ExactWeights(const std::vector<double>& weights) : weights_(weights) {}
  boost::any get(const boost::any& key) override { return weights_[index(key)]; }
  std::string get_string(const boost::any& key) override {
    char text[32];  // the longest shortest form of a double is 24 characters
    const std::to_chars_result r = std::to_chars(text, text + sizeof text, weights_[index(key)]);
    return std::string(text, r.ptr);
  }
  void put(const boost::any&, const boost::any&) override { throw Error("graph export: the weights are read only"); }
  const std::type_info& key() const override { return typeid(ExportGraph::edge_descriptor); }
  const std::type_info& value() const override { return typeid(double); }

 private:
  static std::size_t index(const boost::any& key) { return boost::any_cast<ExportGraph::edge_descriptor>(key).idx; }
  const std::vector<double>& weights_;
};

std::string kind_names(std::uint8_t kinds) {
  std::string s;
  if (kinds & kOnsetNode) s += "onset ";
  if (kinds & kKeywordNode) s += "keyword ";
  if (kinds & kBreakNode) s += "break ";
  if (!s.empty()) s.pop_back();
  return s.empty() ? "regular" : s;
}

}  // namespace

void graph_write_dot(const std::string& path, const MotionGraph& g, int from, int to) {
  const Part part = subgraph(g, from, to);
  const ExportGraph& sub = part.graph;
  write_file_atomically(path, [&](std::ostream& out) {
    boost::write_graphviz(
        out, sub,
        [&](std::ostream& os, std::size_t v) {
          const NodeInfo& n = sub[v];
          os << "[label=\"" << (from + static_cast<int>(v));
          if (n.kinds & kKeywordNode) os << "\\n" << n.keyword;
          os << "\"";
          if (n.kinds & kBreakNode)
            os << ", shape=box, color=red";
          else if (n.kinds & kKeywordNode)
            os << ", shape=doublecircle, color=blue";
          else if (n.kinds & kOnsetNode)
            os << ", shape=circle, color=darkgreen";
          os << "]";
        },
        [&](std::ostream& os, const ExportGraph::edge_descriptor& e) {
          if (is_natural_edge(boost::source(e, sub), boost::target(e, sub)))
            os << "[color=gray]";
          else
            os << "[color=orange, label=\"" << part.weight[e.idx] << "\"]";
        });
  });
}

void graph_write_graphml(const std::string& path, const MotionGraph& g, int from, int to) {
  const Part part = subgraph(g, from, to);
  const ExportGraph& sub = part.graph;
  std::vector<int> frame(boost::num_vertices(sub));
  std::vector<std::string> kinds(boost::num_vertices(sub)), keyword(boost::num_vertices(sub));
  for (std::size_t v = 0; v < frame.size(); ++v) {
    frame[v] = from + static_cast<int>(v);
    kinds[v] = kind_names(sub[v].kinds);
    keyword[v] = sub[v].keyword.str();
  }
  std::vector<bool> natural;  // in edge order (boost::edges of a compressed sparse row graph)
  for (auto [it, end] = boost::edges(sub); it != end; ++it)
    natural.push_back(is_natural_edge(boost::source(*it, sub), boost::target(*it, sub)));
  boost::dynamic_properties dp;
  dp.property("frame", boost::make_iterator_property_map(frame.begin(), boost::get(boost::vertex_index, sub)));
  dp.property("kinds", boost::make_iterator_property_map(kinds.begin(), boost::get(boost::vertex_index, sub)));
  dp.property("keyword", boost::make_iterator_property_map(keyword.begin(), boost::get(boost::vertex_index, sub)));
  dp.insert("weight", boost::make_shared<ExactWeights>(part.weight));
  dp.property("natural", boost::make_iterator_property_map(natural.begin(), boost::get(boost::edge_index, sub)));
  write_file_atomically(path, [&](std::ostream& out) { boost::write_graphml(out, sub, dp, true); });
}

}  // namespace gmg
