#pragma once
// The sensor's side of the wire, for the simulator: one rotation (an OusterFrame) written as the
// lidar packets an Ouster sensor of the metadata's profile sends, framework-free. The inverse of
// ouster_packets.hpp's decoder, field for field: the packet header (type 1, frame id, init id and
// serial from the metadata), each column's header (timestamp, measurement id, status valid when
// the column `received`), each pixel's fields at the positions docs/drivers-formats.md gives, the
// CRC-64 in the footer where the metadata says the firmware appends one. Columns go out in
// measurement-id order within the metadata's column window, `columns_per_packet` to a packet.
// Reserved bytes are zero (a real sensor's footer may hold other bytes: nothing reads them).
#include "ouster_frame.hpp"
#include "ouster_metadata.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::drivers {

// The frame's packets, appended to `packets` (each one the profile's packet size). A range wider
// than its field (19 bits of mm, or 15 bits of 8 mm in the low-data-rate profile) is sent as 0
// (no return), as a sensor sends a return beyond its reach.
void encode_ouster_packets(const OusterFrame& frame, const OusterMetadata& metadata, std::vector<std::vector<uint8_t>>& packets);

// The number of packets a frame goes out in, and packet `index` of them alone (its columns the
// window's index * columns_per_packet on): a sensor sends each as soon as its columns are measured.
int ouster_packets_per_frame(const OusterMetadata& metadata);
std::vector<uint8_t> encode_ouster_packet(const OusterFrame& frame, const OusterMetadata& metadata, int index);

}  // namespace brickyard::drivers
