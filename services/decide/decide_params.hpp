// Parameters of gpilot-decide (section `decide`): the state buffers and the decision tree (the paper's Alg. 3).
#pragma once

#include <string>

#include "config_schema.hpp"

namespace gpilot {

struct DecideParams {
  std::string rule = "evidence";  //!< evidence: EvidenceRule (evidence_rule.hpp, measured: README); paper: Alg. 3
  int buffer_size = 60;         //!< observations kept in S_out and S_front (paper 60)
  int out_threshold = 30;       //!< FINE/UP/DOWN when more than this many non-zero S_out entries (paper 30)
  int front_threshold = 30;     //!< CLOSER/FURTHER when more than this many higher/lower S_front entries (paper 30)
  double lambda4 = 0.5;         //!< x := 0 when |y| > |lambda4 x| (paper 0.5)
  double gap_timeout_s = 0.5;   //!< a gap between observations longer than this empties the buffers
  // rule evidence (frames of evidence; see evidence_rule.hpp)
  int evidence_enter = 3;       //!< a command is entered at this much evidence (a steady pose: this many frames)
  int evidence_leave = 2;       //!< and left when its evidence falls to this
  int evidence_max = 10;        //!< evidence is capped here: letting go takes (max - leave) / decay frames
  double evidence_decay = 1.0;  //!< evidence lost per frame that does not support a command
  double moving_ratio = 0.07;   //!< a hand whose median position over the last moving_frames frames is this many
  int moving_frames = 2;        //!< box widths from its median over the moving_frames before is moving: no evidence
  int direction_frames = 8;     //!< FINE/UP/DOWN direction: mean of the last this many supporting vectors
  int front_hold_frames = 15;   //!< CLOSER/FURTHER: a hand in front supports them once it has been in front this
  double front_hold_ratio = 0.08;  //!< many frames, all within this many box widths of their median (held)
  double front_dead_zone = 0.05;   //!< a hand in front this close to the body centre's height (box widths):
                                   //!< neither CLOSER nor FURTHER

  template <class V>
  void visit(V& v) {
    v("rule", rule, "decision rule: paper (Alg. 3 over the state buffers) or evidence (per-command evidence, hysteresis)");
    v("buffer_size", buffer_size, 1, 10000, "observations kept in each state buffer (paper 60)");
    v("out_threshold", out_threshold, 0, 10000, "non-zero S_out entries needed, more than (paper 30)");
    v("front_threshold", front_threshold, 0, 10000, "higher/lower S_front entries needed, more than (paper 30)");
    v("lambda4", lambda4, 0.0, 100.0, "vertical snap: x := 0 when |y| > |lambda4 x| (paper 0.5)");
    v("gap_timeout_s", gap_timeout_s, 0.01, 60.0, "observation gap that empties the buffers, s");
    v("evidence_enter", evidence_enter, 1, 1000, "evidence: a command is entered at this much evidence, frames");
    v("evidence_leave", evidence_leave, 0, 1000, "evidence: a held command is left when its evidence falls to this");
    v("evidence_max", evidence_max, 1, 1000, "evidence: cap; letting go takes (max - leave) / decay frames");
    v("evidence_decay", evidence_decay, 0.0, 1000.0, "evidence: lost per frame that does not support a command");
    v("moving_ratio", moving_ratio, 0.0, 10.0, "evidence: median hand position shift (box widths) that is moving: no evidence");
    v("moving_frames", moving_frames, 1, 1000, "evidence: frames in each of the two medians compared for moving_ratio");
    v("direction_frames", direction_frames, 1, 1000, "evidence: FINE/UP/DOWN direction is the mean of this many last vectors");
    v("front_hold_frames", front_hold_frames, 1, 1000, "evidence: a hand in front this many frames, held still, supports CLOSER/FURTHER");
    v("front_hold_ratio", front_hold_ratio, 0.0, 10.0, "evidence: held still: those frames within this many box widths of their median");
    v("front_dead_zone", front_dead_zone, 0.0, 1.0, "evidence: a hand in front this close to the body centre's height (box widths) is neither CLOSER nor FURTHER");
  }
  void check(const ParamCheck& c) const {
    c.choice("rule", rule, {"paper", "evidence"});
    // "More than the threshold" of a buffer_size buffer: a threshold of buffer_size or more never decides.
    c.require(out_threshold < buffer_size, "out_threshold",
              std::to_string(out_threshold) + " must be below buffer_size " + std::to_string(buffer_size));
    c.require(front_threshold < buffer_size, "front_threshold",
              std::to_string(front_threshold) + " must be below buffer_size " + std::to_string(buffer_size));
    // Evidence is capped at evidence_max, so a higher evidence_enter is never reached; a command left at
    // evidence_enter or above would be left the frame it was entered.
    c.require(evidence_enter <= evidence_max, "evidence_enter",
              std::to_string(evidence_enter) + " must be at most evidence_max " + std::to_string(evidence_max));
    c.require(evidence_leave < evidence_enter, "evidence_leave",
              std::to_string(evidence_leave) + " must be below evidence_enter " + std::to_string(evidence_enter));
  }
};

// Decide's section of the config file (services/system assembles the whole file from every stage's).
inline void add_decide_sections(ConfigSchema& schema) { schema.section<DecideParams>("decide"); }

}  // namespace gpilot
