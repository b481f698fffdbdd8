#include "common/sim/frame_storage.h"

#include <algorithm>
#include <utility>

namespace hs {

void ClearPairContacts(std::vector<PairContact>& contacts, std::vector<ContactSet>& spare) {
  for (PairContact& pair : contacts) spare.push_back(std::move(pair.contact));
  contacts.clear();
}

PairContact& AddPairContact(std::vector<PairContact>& contacts, std::vector<ContactSet>& spare) {
  PairContact& pair = contacts.emplace_back();
  if (!spare.empty()) {
    pair.contact = std::move(spare.back());
    spare.pop_back();
  }
  ClearContactSet(pair.contact);
  return pair;
}

void CopyFrame(const StepFrame& from, StepFrame& to, FrameCopyStorage& storage) {
  for (const ToolFrame& tool : from.tools) {
    for (const PairContact& pair : tool.contacts) {
      for (const SideContact* side : {&pair.contact.moving, &pair.contact.fixed}) {
        storage.most_features = std::max(
            {storage.most_features, side->vertices.size(), side->edges.size(), side->faces.size()});
      }
      storage.most_points = std::max(storage.most_points, pair.contact.points.size());
    }
  }
  to.tools.resize(from.tools.size());  // as many as the scene has tools
  for (size_t i = 0; i < from.tools.size(); ++i) {
    std::vector<PairContact>& pairs = to.tools[i].contacts;
    while (pairs.size() > from.tools[i].contacts.size()) {
      storage.spare.push_back(std::move(pairs.back().contact));
      pairs.pop_back();
    }
    while (pairs.size() < from.tools[i].contacts.size()) AddPairContact(pairs, storage.spare);
    for (PairContact& pair : pairs) {
      for (SideContact* side : {&pair.contact.moving, &pair.contact.fixed}) {
        side->vertices.reserve(storage.most_features);
        side->edges.reserve(storage.most_features);
        side->faces.reserve(storage.most_features);
      }
      pair.contact.points.reserve(storage.most_points);
    }
  }
  // Every vector now has its source's length and room for its contents:
  // the copy assigns element by element, into the storage there is.
  to = from;
}

}  // namespace hs
