// StateBuffer: a fixed ring of the last N hand vectors with the counts Alg. 3 reads.
#include "state_buffer.hpp"

#include <algorithm>

namespace gpilot {

StateBuffer::StateBuffer(int capacity) : entries_(static_cast<size_t>(std::max(1, capacity))) {}

void StateBuffer::push(Vec2 v) {
  entries_[next_] = v;
  next_ = (next_ + 1) % entries_.size();
  count_ = std::min(count_ + 1, entries_.size());
}

void StateBuffer::clear() {
  next_ = 0;
  count_ = 0;
}

template <class F>
void StateBuffer::for_each(F&& f) const {
  // The live entries are the `count_` slots before next_; order does not matter for counts and means.
  for (size_t i = 0; i < count_; ++i) f(entries_[(next_ + entries_.size() - 1 - i) % entries_.size()]);
}

int StateBuffer::count_nonzero() const {
  int n = 0;
  for_each([&](const Vec2& v) { n += v.is_zero() ? 0 : 1; });
  return n;
}

Vec2 StateBuffer::mean_nonzero() const {
  Vec2 sum;
  int n = 0;
  for_each([&](const Vec2& v) {
    if (v.is_zero()) return;
    sum.x += v.x;
    sum.y += v.y;
    ++n;
  });
  if (n == 0) return {};
  return {sum.x / n, sum.y / n};
}

int StateBuffer::count_y_negative() const {
  int n = 0;
  for_each([&](const Vec2& v) { n += v.y < 0.0 ? 1 : 0; });
  return n;
}

int StateBuffer::count_y_positive() const {
  int n = 0;
  for_each([&](const Vec2& v) { n += v.y > 0.0 ? 1 : 0; });
  return n;
}

}  // namespace gpilot
