#pragma once
// capture info's output: a pcap's or a GNSS log's findings as text for a person
// (capture_report_text.cpp) or as JSON (capture_report_json.cpp), on stdout.
#include "cli/capture_gnss.hpp"
#include "cli/capture_pcap.hpp"

#include <cstdint>
#include <string>

namespace brickyard::fw::cli {

void print_pcap_text(const std::string& file, std::uint64_t bytes, const PcapInfo& info);
void print_pcap_json(const std::string& file, std::uint64_t bytes, const PcapInfo& info);
void print_gnss_text(const std::string& file, std::uint64_t bytes, const GnssLogInfo& info);
void print_gnss_json(const std::string& file, std::uint64_t bytes, const GnssLogInfo& info);

}  // namespace brickyard::fw::cli
