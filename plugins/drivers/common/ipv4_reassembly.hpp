#pragma once
// IPv4 fragment reassembly (RFC 791), framework-free and bounded: a UDP datagram larger than the
// link's MTU (an OS-2-128 lidar packet is 24,832 bytes; Ethernet carries 1,500) arrives as
// fragments that share the sender, receiver, protocol and identification, each holding the bytes
// at its fragment offset; the last has "more fragments" clear. A datagram is handed back once every
// byte up to the last fragment's end has arrived, in any order. Fragments that overlap without
// repeating, run past 65,535 bytes, or belong to datagrams pushed out by newer ones (more than
// kMaxPending at once) are counted dropped with their datagram.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace brickyard::drivers {

struct Ipv4FragmentKey {
  uint32_t source = 0;
  uint32_t destination = 0;
  uint16_t identification = 0;
  uint8_t protocol = 0;
  bool operator==(const Ipv4FragmentKey&) const = default;
};

class Ipv4Reassembler {
 public:
  static constexpr size_t kMaxPending = 16;
  static constexpr size_t kMaxDatagramBytes = 65535 - 20;  // an IPv4 payload's largest

  // Takes one fragment's payload, at byte `offset` of its datagram. Returns the whole datagram's
  // payload when this fragment completes it (valid until the next call).
  std::optional<std::span<const uint8_t>> add(const Ipv4FragmentKey& key, size_t offset, bool more_fragments,
                                              std::span<const uint8_t> data);
  // The stream has ended: datagrams still incomplete are dropped with their fragments.
  void finish();

  uint64_t fragments_dropped() const { return dropped_; }
  size_t pending() const { return pending_.size(); }

 private:
  struct Pending {
    Ipv4FragmentKey key;
    std::vector<uint8_t> bytes;
    std::vector<std::pair<size_t, size_t>> pieces;  // [begin, end) of the fragments held
    size_t received = 0;                             // bytes held, pieces not overlapping
    std::optional<size_t> total;                     // known once the last fragment came
    uint64_t arrival = 0;
  };
  Pending& find_or_open(const Ipv4FragmentKey& key);
  bool store(Pending& p, size_t offset, bool more_fragments, std::span<const uint8_t> data);
  void drop(size_t index);

  std::vector<Pending> pending_;
  std::vector<uint8_t> done_;
  uint64_t arrivals_ = 0;
  uint64_t dropped_ = 0;
};

}  // namespace brickyard::drivers
