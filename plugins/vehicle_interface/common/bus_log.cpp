#include "bus_log.hpp"

namespace brickyard::vehicle_interface {

void BusLog::add(const std::vector<CanFrame>& frames, int64_t stamp_ns, bool sent) {
  for (const CanFrame& f : frames) {
    LoggedFrame& l = frames_.emplace_back();
    l.stamp_ns = stamp_ns;
    l.sent = sent;
    l.frame = f;
    l.message = f.remote ? nullptr : db_.find(f.id, f.extended);
    if (!l.message || !decode_ || l.message->independent_signals) continue;
    UnpackResult u = unpack_message(*l.message, f);
    if (u.ok()) l.signals = std::move(u.values);
    else ++undecoded_;
  }
}

}  // namespace brickyard::vehicle_interface
