#include "ouster_packets.hpp"

#include <utility>

namespace brickyard::drivers {

namespace {

constexpr uint16_t kLidarPacketType = 1;

// Frame ids are 16 bits and wrap: b is after a when it is less than half the range ahead.
int16_t frames_ahead(uint16_t from, uint16_t to) { return static_cast<int16_t>(static_cast<uint16_t>(to - from)); }

}  // namespace

OusterLidarDecoder::OusterLidarDecoder(OusterMetadata metadata, OusterDecoderOptions options)
    : metadata_(std::move(metadata)), options_(options), layout_(ouster_packet_layout(metadata_)) {}

void OusterLidarDecoder::feed(const uint8_t* data, size_t size) {
  ++counters_.packets;
  uint16_t frame_id = 0;
  if (!accept_packet(data, size, frame_id)) return;
  if (!columns_in_range(data, frame_id)) {
    ++counters_.bad_column;
    return;
  }
  if (!route_to_frame(frame_id)) {
    ++counters_.late;
    return;
  }
  place_columns(data);
  ++counters_.decoded;
  if (current_->complete()) hand_out_current();
}

// Size, CRC, packet type and identity, in that order: each refusal is counted under one reason.
bool OusterLidarDecoder::accept_packet(const uint8_t* data, size_t size, uint16_t& frame_id) {
  if (data == nullptr || size != layout_.packet_bytes()) {
    ++counters_.bad_size;
    return false;
  }
  if (layout_.profile == OusterProfile::legacy) {  // no packet header: the first column says
    frame_id = read_ouster_column_header(layout_, data).frame_id;
    return true;
  }
  if (options_.check_crc && metadata_.packet_crc && !ouster_packet_crc_ok(data, size)) {
    ++counters_.bad_crc;
    return false;
  }
  header_ = read_ouster_packet_header(data);
  if (header_.packet_type != kLidarPacketType) {
    ++counters_.bad_packet_type;
    return false;
  }
  bool serial_differs = metadata_.serial_number != 0 && header_.serial_number != metadata_.serial_number;
  bool init_differs = metadata_.initialization_id != 0 && header_.initialization_id != metadata_.initialization_id;
  if (options_.check_identity && (serial_differs || init_differs)) {
    ++counters_.wrong_sensor;
    return false;
  }
  frame_id = header_.frame_id;
  return true;
}

// Every column must fit the frame (and, in LEGACY packets, belong to the packet's frame) before
// any is placed, so a packet is decoded whole or not at all.
bool OusterLidarDecoder::columns_in_range(const uint8_t* data, uint16_t frame_id) {
  const uint8_t* column = data + layout_.header_bytes;
  for (int c = 0; c < layout_.columns_per_packet; ++c, column += layout_.column_bytes()) {
    OusterColumnHeader h = read_ouster_column_header(layout_, column);
    if (h.measurement_id >= metadata_.columns_per_frame) return false;
    if (layout_.profile == OusterProfile::legacy && h.frame_id != frame_id) return false;
  }
  return true;
}

// Makes `frame_id`'s frame the current one; false when the packet is late.
bool OusterLidarDecoder::route_to_frame(uint16_t frame_id) {
  if (current_ && current_->frame_id == frame_id) return true;
  if (current_) {
    if (frames_ahead(current_->frame_id, frame_id) < 0) return false;
    hand_out_current();  // a later frame began: this one will get no more columns
  }
  if (last_handed_out_) {
    int16_t ahead = frames_ahead(*last_handed_out_, frame_id);
    if (ahead <= 0) return false;
    counters_.skipped_frames += static_cast<uint64_t>(ahead - 1);
  }
  if (!spare_.empty()) {
    current_ = std::move(spare_.front());
    spare_.pop_front();
  } else {
    current_.emplace();
  }
  reset_ouster_frame(*current_, metadata_, frame_id);
  previous_first_column_ = -1;
  return true;
}

void OusterLidarDecoder::place_columns(const uint8_t* data) {
  OusterFrame& f = *current_;
  if (layout_.profile != OusterProfile::legacy) f.last_header = header_;
  const uint8_t* column = data + layout_.header_bytes;
  for (int c = 0; c < layout_.columns_per_packet; ++c, column += layout_.column_bytes()) {
    OusterColumnHeader h = read_ouster_column_header(layout_, column);
    const int id = h.measurement_id;
    if (c == 0 && id < previous_first_column_) ++counters_.out_of_order;
    if (c == 0) previous_first_column_ = id;
    if (f.received[id]) {
      ++counters_.duplicate_columns;
      continue;
    }
    f.timestamp_ns[id] = h.timestamp_ns;
    f.encoder_count[id] = h.encoder_count;
    f.status[id] = h.status;
    if (!h.valid) {  // the sensor sends its header but zeroed pixels
      ++counters_.invalid_columns;
      continue;
    }
    read_ouster_pixels(layout_, column + layout_.column_header_bytes, id, f);
    f.received[id] = 1;
    if (metadata_.column_in_window(id)) ++f.columns_received;
  }
}

void OusterLidarDecoder::hand_out_current() {
  OusterFrame& f = *current_;
  finish_ouster_frame(f);
  if (f.complete()) {
    ++counters_.frames_complete;
  } else {
    ++counters_.frames_incomplete;
    counters_.missing_columns += static_cast<uint64_t>(f.columns_expected - f.columns_received);
  }
  last_handed_out_ = f.frame_id;
  ready_.push_back(std::move(f));
  current_.reset();
}

std::optional<OusterFrame> OusterLidarDecoder::next() {
  if (ready_.empty()) return std::nullopt;
  OusterFrame f = std::move(ready_.front());
  ready_.pop_front();
  return f;
}

void OusterLidarDecoder::recycle(OusterFrame&& frame) {
  if (spare_.size() < 2) spare_.push_back(std::move(frame));
}

void OusterLidarDecoder::finish() {
  if (current_) hand_out_current();
}

}  // namespace brickyard::drivers
