// SPDX-License-Identifier: MIT
// A pointer and a count: how the runtime takes caller-owned memory (C++17 has
// no std::span). Never owns, never allocates.
#pragma once
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace posemorph {

// A string in a rig's arena (not NUL-terminated).
struct StringView {
  const char* data = nullptr;
  std::size_t size = 0;
};

template <typename T>
struct Span {
  T* data = nullptr;
  std::size_t size = 0;

  constexpr Span() = default;
  constexpr Span(T* d, std::size_t n) : data(d), size(n) {}
  template <std::size_t N>
  constexpr Span(T (&a)[N]) : data(a), size(N) {}
  // Span<const T> from Span<T>.
  template <typename U>
  constexpr Span(const Span<U>& o) : data(o.data), size(o.size) {}

  constexpr T& operator[](std::size_t i) const { return data[i]; }
  constexpr T* begin() const { return data; }
  constexpr T* end() const { return data + size; }
  constexpr bool empty() const { return size == 0; }
  // The `count` elements from `offset`, which must lie within this span
  // (asserted in debug builds; release builds trust the caller's Validate()).
  constexpr Span subspan(std::size_t offset, std::size_t count) const {
    assert(offset <= size && count <= size - offset);
    return {data + offset, count};
  }
};

// A span over a container with data() and size() (std::vector, std::array),
// or over a C array.
template <typename Container>
auto MakeSpan(Container& c) -> Span<typename std::remove_reference<decltype(*c.data())>::type> {
  return {c.data(), c.size()};
}
template <typename T, std::size_t N>
constexpr Span<T> MakeSpan(T (&a)[N]) {
  return {a, N};
}

}  // namespace posemorph
