// Parameters of gpilot-decide (section `decide`): the state buffers and the decision tree (the paper's Alg. 3).
#pragma once

namespace gpilot {

struct DecideParams {
  int buffer_size = 60;         //!< observations kept in S_out and S_front (paper 60)
  int out_threshold = 30;       //!< FINE/UP/DOWN when more than this many non-zero S_out entries (paper 30)
  int front_threshold = 30;     //!< CLOSER/FURTHER when more than this many higher/lower S_front entries (paper 30)
  double lambda4 = 0.5;         //!< x := 0 when |y| > |lambda4 x| (paper 0.5)
  double gap_timeout_s = 0.5;   //!< a gap between observations longer than this empties the buffers

  template <class V>
  void visit(V& v) {
    v("buffer_size", buffer_size, 1, 10000, "observations kept in each state buffer (paper 60)");
    v("out_threshold", out_threshold, 0, 10000, "non-zero S_out entries needed, more than (paper 30)");
    v("front_threshold", front_threshold, 0, 10000, "higher/lower S_front entries needed, more than (paper 30)");
    v("lambda4", lambda4, 0.0, 100.0, "vertical snap: x := 0 when |y| > |lambda4 x| (paper 0.5)");
    v("gap_timeout_s", gap_timeout_s, 0.01, 60.0, "observation gap that empties the buffers, s");
  }
};

}  // namespace gpilot
