// StateBuffer: the paper's S_out / S_front, the last N per-frame hand vectors (zero = nothing found).
#pragma once

#include <cstddef>
#include <vector>

namespace gpilot {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  bool is_zero() const { return x == 0.0 && y == 0.0; }
};

class StateBuffer {
 public:
  explicit StateBuffer(int capacity);

  // Appends one frame's result, dropping the oldest once the buffer holds `capacity` entries.
  void push(Vec2 v);
  void clear();

  int size() const { return static_cast<int>(count_); }
  int capacity() const { return static_cast<int>(entries_.size()); }

  int count_nonzero() const;
  // Mean over the non-zero entries only; (0, 0) when there are none.
  Vec2 mean_nonzero() const;
  int count_y_negative() const;  // "higher": image y points down
  int count_y_positive() const;  // "lower"

 private:
  template <class F>
  void for_each(F&& f) const;

  std::vector<Vec2> entries_;
  size_t next_ = 0;
  size_t count_ = 0;
};

}  // namespace gpilot
