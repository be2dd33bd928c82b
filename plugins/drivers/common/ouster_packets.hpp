#pragma once
// A decoder of Ouster lidar packets into frames, framework-free: each UDP payload from the lidar
// port in, whole rotations out, no I/O, no exceptions on bad input. A packet is checked against the
// metadata's profile (its size), its CRC-64 where the firmware appends one, its packet type and
// the sensor's serial and init id; a packet that fails is counted under one reason and dropped,
// never decoded. Columns are placed by measurement id into the frame their frame id names; a frame
// is handed out when every column of the column window has arrived, or, short of that, when a
// packet of a later frame arrives (or finish() is called), with its missing columns counted.
// Packets of a frame already handed out are counted late and dropped. Formats and sources:
// docs/drivers-formats.md, "Ouster LiDAR packets"; points from a frame: ouster_xyz.hpp.
#include "ouster_frame.hpp"
#include "ouster_metadata.hpp"
#include "ouster_packet_format.hpp"

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

namespace brickyard::drivers {

// What the decoder did with the packets it was fed. Every dropped packet is counted under exactly
// one of the refusal reasons; frame and column counts describe what was assembled.
struct OusterCounters {
  uint64_t packets = 0;          // payloads fed
  uint64_t decoded = 0;          // packets whose columns went into a frame
  uint64_t bad_size = 0;         // size is not the profile's packet size (truncated, padded, other profile)
  uint64_t bad_crc = 0;          // the firmware's CRC-64 does not match
  uint64_t bad_packet_type = 0;  // the header's packet type is not 1 (lidar)
  uint64_t wrong_sensor = 0;     // serial or init id differs from the metadata's
  uint64_t bad_column = 0;       // a measurement id past the frame's width, or (LEGACY) a frame id
                                 // differing from the packet's first column: the packet is dropped
  uint64_t late = 0;             // of a frame already handed out, or older than the current one

  uint64_t out_of_order = 0;      // decoded, but its first column precedes the previous packet's
  uint64_t duplicate_columns = 0; // columns that had already arrived (the later copy is dropped)
  uint64_t invalid_columns = 0;   // columns the sensor marked invalid (dropped by it, or outside the window)
  uint64_t frames_complete = 0;
  uint64_t frames_incomplete = 0;  // handed out with columns of the window missing
  uint64_t missing_columns = 0;    // the window's columns absent from the frames handed out
  uint64_t skipped_frames = 0;     // frame ids jumped over: whole rotations never seen

  uint64_t refused() const { return bad_size + bad_crc + bad_packet_type + wrong_sensor + bad_column + late; }
};

struct OusterDecoderOptions {
  bool check_crc = true;       // when the metadata says the firmware appends one
  bool check_identity = true;  // serial and init id against the metadata's, where it gives them
};

class OusterLidarDecoder {
 public:
  explicit OusterLidarDecoder(OusterMetadata metadata, OusterDecoderOptions options = {});

  // One UDP payload from the lidar port.
  void feed(const uint8_t* data, size_t size);
  // The next frame handed out, oldest first; nothing when none is waiting.
  std::optional<OusterFrame> next();
  // Gives a frame's buffers back for reuse, so a steady stream allocates nothing per frame.
  void recycle(OusterFrame&& frame);
  // The stream has ended: the frame in progress is handed out, complete or not.
  void finish();

  const OusterCounters& counters() const { return counters_; }
  const OusterMetadata& metadata() const { return metadata_; }
  const OusterPacketLayout& layout() const { return layout_; }

 private:
  bool accept_packet(const uint8_t* data, size_t size, uint16_t& frame_id);
  bool columns_in_range(const uint8_t* data, uint16_t frame_id);
  bool route_to_frame(uint16_t frame_id);
  void place_columns(const uint8_t* data);
  void hand_out_current();

  OusterMetadata metadata_;
  OusterDecoderOptions options_;
  OusterPacketLayout layout_;
  OusterPacketHeader header_;  // of the packet being fed (non-LEGACY)
  std::optional<OusterFrame> current_;
  std::optional<uint16_t> last_handed_out_;
  int previous_first_column_ = -1;
  std::deque<OusterFrame> ready_;
  std::deque<OusterFrame> spare_;
  OusterCounters counters_;
};

}  // namespace brickyard::drivers
