// The element nearest in time: the one lookup the factor source (a measurement's state) and the
// trust check (a GNSS fix's estimate) share.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>

namespace slipgraph {

// The index of the element of `sorted` (ascending in time(element)) nearest in time to `t`;
// ties go to the earlier element. `sorted` must not be empty.
template <typename Range, typename Time>
size_t NearestInTime(const Range& sorted, double t, Time time) {
  const auto begin = std::begin(sorted), end = std::end(sorted);
  const auto it = std::lower_bound(
      begin, end, t, [&](const auto& element, double value) { return time(element) < value; });
  if (it == begin) return 0;
  const size_t after = static_cast<size_t>(it - begin);
  if (it == end) return after - 1;
  return t - time(*(it - 1)) <= time(*it) - t ? after - 1 : after;
}

}  // namespace slipgraph
