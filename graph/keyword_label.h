// The keyword label of a graph node (graph/motion_graph.h NodeInfo): a 32-bit handle to one copy
// of its text, so a node is 8 bytes instead of 40 (a std::string each) and a loaded hour of
// reference copies 8 MB of nodes, not 40.
//
// Labels are interned in one table for the process, shared by every graph and never emptied:
// a graph's labels are the keywords of its speech (a lexicon's words and phrases), so the table
// holds a few hundred texts, whatever the number of graphs or nodes. Thread-safe.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>

namespace gmg {

class KeywordLabel {
 public:
  KeywordLabel() = default;  // no label: empty() and str() == ""
  // The label with this text (the empty text is no label). Implicit: labels are assigned and
  // compared as the strings they hold.
  KeywordLabel(std::string_view text);  // NOLINT(google-explicit-constructor)
  // NOLINTNEXTLINE(google-explicit-constructor)
  KeywordLabel(const std::string& text) : KeywordLabel(std::string_view(text)) {}
  // NOLINTNEXTLINE(google-explicit-constructor)
  KeywordLabel(const char* text) : KeywordLabel(std::string_view(text)) {}

  bool empty() const { return id_ == 0; }
  // The text; the reference stays valid for the life of the process.
  const std::string& str() const;

  friend bool operator==(KeywordLabel a, KeywordLabel b) { return a.id_ == b.id_; }
  friend bool operator!=(KeywordLabel a, KeywordLabel b) { return a.id_ != b.id_; }
  friend bool operator==(KeywordLabel a, std::string_view text) { return a.str() == text; }
  friend bool operator!=(KeywordLabel a, std::string_view text) { return a.str() != text; }
  friend bool operator==(KeywordLabel a, const std::string& text) { return a.str() == text; }
  friend bool operator!=(KeywordLabel a, const std::string& text) { return a.str() != text; }
  friend bool operator==(KeywordLabel a, const char* text) { return a.str() == text; }
  friend bool operator!=(KeywordLabel a, const char* text) { return a.str() != text; }
  friend std::ostream& operator<<(std::ostream& os, KeywordLabel a) { return os << a.str(); }

 private:
  std::uint32_t id_ = 0;
};

}  // namespace gmg
