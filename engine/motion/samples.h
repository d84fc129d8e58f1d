// An array of motion samples that either owns its values (a std::vector) or reads them in place
// from memory another object keeps alive (a graph file's mapping, graph/graph_io.h). Reading is
// the same for both; the first change to a viewed array copies it (copy on write), so code that
// makes or edits motion works as on a vector while a graph served from its file is never copied.
// Copying a Samples that views shares the view (and keeps its owner alive), so workers that copy
// a served graph's motion still read the one mapping.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "engine/core/files.h"

namespace gmg {

template <typename T>
class Samples {
 public:
  using value_type = T;
  using size_type = std::size_t;
  using iterator = T*;
  using const_iterator = const T*;

  Samples() = default;
  Samples(std::vector<T> values) : own_(std::move(values)) {}  // NOLINT(google-explicit-constructor)
  // size values at data, read in place while `owner` lives.
  static Samples view(const T* data, std::size_t size, const std::shared_ptr<const void>& owner) {
    Samples s;
    s.view_ = data;
    s.view_size_ = size;
    s.owner_ = owner;
    return s;
  }

  // Gives the pages of values [first, first + count) back to the page cache when they are read in
  // place from a file's mapping (a pass over a large array then leaves nothing resident; a later
  // read maps them again); nothing for values in memory.
  void release_pages(std::size_t first, std::size_t count) const {
    if (is_view()) release_mapped_pages(view_ + first, count * sizeof(T));
  }

  // True when the values are read in place from another object's memory.
  bool is_view() const { return owner_ != nullptr; }

  std::size_t size() const { return is_view() ? view_size_ : own_.size(); }
  bool empty() const { return size() == 0; }
  const T* data() const { return is_view() ? view_ : own_.data(); }
  const T& operator[](std::size_t i) const { return data()[i]; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size(); }
  const T& front() const { return data()[0]; }
  const T& back() const { return data()[size() - 1]; }

  // Every change goes through the owned vector (a view is copied into it first).
  std::vector<T>& vec() {
    if (is_view()) {
      own_.assign(view_, view_ + view_size_);
      view_ = nullptr;
      view_size_ = 0;
      owner_.reset();
    }
    return own_;
  }
  T* data() { return vec().data(); }
  T& operator[](std::size_t i) { return vec()[i]; }
  T* begin() { return vec().data(); }
  T* end() { return vec().data() + own_.size(); }
  void push_back(const T& v) { vec().push_back(v); }
  void reserve(std::size_t n) { vec().reserve(n); }
  void resize(std::size_t n) { vec().resize(n); }
  void resize(std::size_t n, const T& v) { vec().resize(n, v); }
  void assign(std::size_t n, const T& v) { drop_view().assign(n, v); }
  template <typename It>
  void assign(It first, It last) {
    std::vector<T> values(first, last);  // first..last may lie in this array's own view
    drop_view() = std::move(values);
  }
  template <typename It>
  void insert(const T* at, It first, It last) {
    const std::size_t offset = static_cast<std::size_t>(at - static_cast<const Samples&>(*this).data());
    std::vector<T>& v = vec();
    v.insert(v.begin() + static_cast<std::ptrdiff_t>(offset), first, last);
  }
  void clear() { drop_view().clear(); }

  friend bool operator==(const Samples& a, const Samples& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
  }
  friend bool operator!=(const Samples& a, const Samples& b) { return !(a == b); }

 private:
  std::vector<T>& drop_view() {
    view_ = nullptr;
    view_size_ = 0;
    owner_.reset();
    return own_;
  }
  std::vector<T> own_;
  const T* view_ = nullptr;
  std::size_t view_size_ = 0;
  std::shared_ptr<const void> owner_;
};

}  // namespace gmg
