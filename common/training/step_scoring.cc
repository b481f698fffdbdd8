#include "common/training/step_scoring.h"

namespace hs {

ScoringFrame ScoringFrameFromStep(const StepFrame& frame, ObjectId tool,
                                  const std::vector<std::string>& names) {
  ScoringFrame out{.time_s = frame.time_s};
  for (const ToolFrame& t : frame.tools) {
    if (t.tool != tool) continue;
    out.p_WD = t.X_WD.translation();
    out.force_W = t.force_W;
    for (const PairContact& c : t.contacts) {
      ScoringContact contact{.object = names[c.object]};
      for (const ContactPoint& p : c.contact.points) contact.points_W.push_back(p.p_WC);
      out.contacts.push_back(std::move(contact));
    }
  }
  return out;
}

}  // namespace hs
