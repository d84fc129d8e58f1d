#include "search/anchors.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace gmg {

std::vector<Anchor> rest_anchors(const std::vector<float>& pause, double fps, double rest_min_s, int hold, int lead) {
  std::vector<Anchor> out;
  if (hold < 1) return out;
  const int shortest = std::max(1, static_cast<int>(std::lround(rest_min_s * fps)));
  const int n = static_cast<int>(pause.size());
  for (int i = 0; i < n;) {
    if (pause[static_cast<std::size_t>(i)] < 0.5f) {
      ++i;
      continue;
    }
    int j = i;
    while (j < n && pause[static_cast<std::size_t>(j)] >= 0.5f) ++j;
    if (j - i >= shortest) {
      const int from = std::max(out.empty() ? 0 : out.back().start + out.back().length, i - std::max(0, lead));
      out.push_back({from, i - from + std::min(j - i, hold), Fixed::Rest, -1, i - from});
    }
    i = j;
  }
  return out;
}

namespace {

void check_anchors(const std::vector<Anchor>& anchors, int total) {
  int end = 0;
  for (const Anchor& a : anchors) {
    if (a.length < 1 || a.start < end || a.start + a.length > total)
      throw Error("anchors: overlapping, unsorted or outside the output (frame " + std::to_string(a.start) + ", " +
                  std::to_string(a.length) + " frames, output " + std::to_string(total) + " frames)");
    if (a.kind == Fixed::None) throw Error("anchors: an anchor must be a rest or a pin");
    end = a.start + a.length;
  }
}

// The planned pieces of `subs` inside [from, to), cut at both ends.
void planned_span(const std::vector<Subsequence>& subs, int from, int to, std::vector<Subsequence>& out) {
  for (const Subsequence& s : subs) {
    const int a = std::max(s.start, from), b = std::min(s.start + s.length, to);
    if (a >= b) continue;
    Subsequence piece = s;
    piece.start = a;
    piece.length = b - a;
    if (b < s.start + s.length) {  // cut short: it now ends where an anchor starts
      piece.kind = Termination::Rhythm;
      piece.keyword.clear();
    }
    out.push_back(piece);
  }
}

// Short planned pieces of one span join a neighbour inside it.
void merge_span(std::vector<Subsequence>& span, int min_length) {
  if (span.size() < 2 || min_length <= 1) return;
  std::vector<Subsequence> out;
  for (Subsequence s : span) {
    if (!out.empty() && s.length < min_length) {  // joins the one before: its end and termination
      Subsequence& prev = out.back();
      const int end = s.start + s.length;
      const int start = prev.start;
      prev = s;
      prev.start = start;
      prev.length = end - start;
      continue;
    }
    if (!out.empty() && out.back().length < min_length) {  // a short first piece joins this one
      s.length += s.start - out.back().start;
      s.start = out.back().start;
      out.back() = s;
      continue;
    }
    out.push_back(s);
  }
  span = std::move(out);
}

}  // namespace

std::vector<Subsequence> place_anchors(const std::vector<Subsequence>& subs, const std::vector<Anchor>& anchors,
                                       int min_length) {
  if (anchors.empty() || subs.empty()) return subs;
  const int total = subs.back().start + subs.back().length;
  check_anchors(anchors, total);
  std::vector<Subsequence> out;
  int from = 0;
  for (const Anchor& a : anchors) {
    std::vector<Subsequence> span;
    planned_span(subs, from, a.start, span);
    merge_span(span, min_length);
    if (a.kind == Fixed::Pin && !span.empty()) {
      span.back().kind = Termination::Frame;
      span.back().keyword.clear();
      span.back().stop_frame = a.source;
    }
    out.insert(out.end(), span.begin(), span.end());
    Subsequence fixed;
    fixed.start = a.start;
    fixed.length = a.length;
    fixed.fixed = a.kind;
    fixed.source = a.source;
    fixed.lead = a.lead;
    out.push_back(fixed);
    from = a.start + a.length;
  }
  std::vector<Subsequence> span;
  planned_span(subs, from, total, span);
  merge_span(span, min_length);
  out.insert(out.end(), span.begin(), span.end());
  return out;
}

}  // namespace gmg
