#include "ipv4_reassembly.hpp"

#include <algorithm>

namespace brickyard::drivers {

std::optional<std::span<const uint8_t>> Ipv4Reassembler::add(const Ipv4FragmentKey& key, size_t offset,
                                                              bool more_fragments, std::span<const uint8_t> data) {
  Pending& p = find_or_open(key);
  const size_t index = static_cast<size_t>(&p - pending_.data());
  if (!store(p, offset, more_fragments, data)) {
    dropped_ += 1;  // this fragment, and below those held for its datagram
    drop(index);
    return std::nullopt;
  }
  if (!p.total || p.received != *p.total) return std::nullopt;
  done_ = std::move(p.bytes);
  done_.resize(*p.total);
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
  return std::span<const uint8_t>(done_);
}

Ipv4Reassembler::Pending& Ipv4Reassembler::find_or_open(const Ipv4FragmentKey& key) {
  for (Pending& p : pending_) {
    if (p.key == key) return p;
  }
  if (pending_.size() >= kMaxPending) {  // the oldest is the likeliest to have lost a fragment
    auto oldest = std::min_element(pending_.begin(), pending_.end(),
                                   [](const Pending& a, const Pending& b) { return a.arrival < b.arrival; });
    drop(static_cast<size_t>(oldest - pending_.begin()));
  }
  Pending p;
  p.key = key;
  p.arrival = arrivals_++;
  pending_.push_back(std::move(p));
  return pending_.back();
}

// False when the fragment cannot belong: past the largest datagram, past a known end, a second
// last fragment disagreeing, or overlapping held bytes other than by repeating a fragment exactly.
bool Ipv4Reassembler::store(Pending& p, size_t offset, bool more_fragments, std::span<const uint8_t> data) {
  const size_t end = offset + data.size();
  if (end > kMaxDatagramBytes || (p.total && end > *p.total)) return false;
  if (!more_fragments) {
    if (p.total && *p.total != end) return false;
    for (const auto& piece : p.pieces) {
      if (piece.second > end) return false;
    }
    p.total = end;
  }
  for (const auto& piece : p.pieces) {
    if (piece.first == offset && piece.second == end) return true;  // a repeat: nothing new
    if (offset < piece.second && piece.first < end) return false;
  }
  if (p.bytes.size() < end) p.bytes.resize(end);
  std::copy(data.begin(), data.end(), p.bytes.begin() + static_cast<std::ptrdiff_t>(offset));
  p.pieces.emplace_back(offset, end);
  p.received += data.size();
  return true;
}

void Ipv4Reassembler::drop(size_t index) {
  dropped_ += pending_[index].pieces.size();
  pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
}

void Ipv4Reassembler::finish() {
  while (!pending_.empty()) drop(pending_.size() - 1);
}

}  // namespace brickyard::drivers
