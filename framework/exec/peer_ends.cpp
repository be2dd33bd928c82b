#include "exec/peer_ends.hpp"

#include <brickyard/msgs/Blob.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <thread>

namespace brickyard::fw {

namespace {
constexpr const char* kBlob = "brickyard::msgs::Blob";
constexpr std::size_t kMaxRecordBytes = 64 * 1024;  // a reason is a line or two

std::optional<RunResult> result_named(const std::string& name) {
  for (RunResult r : {RunResult::success, RunResult::failed, RunResult::interrupted, RunResult::invalid_input})
    if (name == to_string(r)) return r;
  return std::nullopt;
}
}  // namespace

std::vector<std::uint8_t> encode_end(const PeerEnd& end) {
  const std::string text = nlohmann::json{{"result", to_string(end.result)}, {"reason", end.reason}}.dump(
      -1, ' ', false, nlohmann::json::error_handler_t::replace);
  return {text.begin(), text.end()};
}

std::optional<PeerEnd> decode_end(const std::vector<std::uint8_t>& bytes) {
  if (bytes.size() > kMaxRecordBytes) return std::nullopt;
  const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
  if (!j.is_object() || !j.contains("result") || !j["result"].is_string() || !j.contains("reason") || !j["reason"].is_string())
    return std::nullopt;
  const std::optional<RunResult> r = result_named(j["result"].get<std::string>());
  if (!r) return std::nullopt;
  return PeerEnd{*r, j["reason"].get<std::string>()};
}

PeerEnds::PeerEnds(DdsTransport& t, const std::string& me, const std::set<std::string>& processes, Heard heard) : me_(me) {
  writer_ = t.make_writer(end_topic(me), kBlob);
  for (const std::string& p : processes) {
    if (p == me) continue;
    auto peer = std::make_unique<Peer>();
    Peer* q = peer.get();
    WriterCheck check;
    check.expected = participant_name(p);
    peer->reader = t.make_reader(
        end_topic(p), kBlob, 4,
        [q, p, heard](std::shared_ptr<const void> s) {
          if (q->said.exchange(true)) return;  // the first word is the end
          const auto& blob = *static_cast<const msgs::Blob*>(s.get());
          const std::optional<PeerEnd> end = decode_end(blob.data());
          heard(p, end ? *end : PeerEnd{RunResult::failed, "it sent a damaged end record"});
        },
        [q](bool alive) {
          if (alive) q->met = true;
        },
        std::move(check));
    peers_.emplace(p, std::move(peer));
  }
}

std::vector<std::string> PeerEnds::left_unsaid(double grace_s) {
  auto unsaid = [&] {
    std::vector<std::string> out;
    for (const auto& [p, q] : peers_)
      if (q->met && q->reader->matched() == 0 && !q->said) out.push_back(p);
    return out;
  };
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
  std::vector<std::string> out = unsaid();
  while (!out.empty() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    out = unsaid();
  }
  return out;
}

void PeerEnds::say(const PeerEnd& end, double seconds) {
  msgs::Blob b;
  b.header().frame_id(me_);
  b.data() = encode_end(end);
  writer_->write(&b);
  writer_->wait_acked(seconds);
}

}  // namespace brickyard::fw
