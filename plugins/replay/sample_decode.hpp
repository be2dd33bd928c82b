#pragma once
// A recorded sample's CDR bytes decoded into its message, as Fast DDS would, for the replay plugins
// (plugin.cpp). Plugin-side: messages and fastcdr.
#include <brickyard/msgs/PointCloud.h>
#include <brickyard/msgs/QuantizedPointCloud.h>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include "cloud/quantized_cloud.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace brickyard::replay {

// Decodes one recorded sample as Fast DDS would; when the bytes do not fit the type, says how many
// did (a damaged sample was "Cdr::read_encapsulation", with no place).
template <class T> std::string decode(const std::vector<unsigned char>& data, T& m) {
  std::vector<char> bytes(data.begin(), data.end());  // fastcdr reads through a mutable buffer
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  try {
    cdr.read_encapsulation();
    m.deserialize(cdr);
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    return "its first " + std::to_string(cdr.getSerializedDataLength()) + " of " + std::to_string(data.size()) +
           " bytes decode, the next do not (" + e.what() + ")";
  }
  return {};
}

// One sample of a replay node of T: `packed`, a cloud recorded compact (--record-cloud-precision,
// T is PointCloud) unpacked into the PointCloud it was. Returns why it does not decode; empty: it did.
template <class T> std::string decode_sample(const std::vector<unsigned char>& data, bool packed, T& m) {
  std::string e;
  if constexpr (std::is_same_v<T, msgs::PointCloud>) {
    if (packed) {
      msgs::QuantizedPointCloud q;
      e = decode(data, q);
      try {
        if (e.empty()) m = cloud::unpack<msgs::PointCloud>(q);
      } catch (const std::invalid_argument& x) {
        e = x.what();
      }
    }
  }
  if (!packed) e = decode(data, m);
  return e;
}

}  // namespace brickyard::replay
