#pragma once
// `brickyard run --live PORT`: a Foxglove WebSocket server (protocol foxglove.websocket.v1) so a
// person watches the run in Foxglove as it happens. It advertises every wire of this process as a
// channel (CDR messages, the type's OMG IDL as schema) and streams a channel's samples to the
// clients subscribed to it; on the sim clock it also sends the run's time. Bound to 127.0.0.1
// unless told otherwise.
//
// The run never waits for it: the server has its own thread (asio); a sample is handed over as
// bytes into each subscriber's queue, and a subscriber whose queue holds more than `max_queue`
// bytes (a slow or stalled client) loses samples (counted) rather than slowing the run. A client
// that sends garbage gets a status message; one that floods requests or sends an oversized
// message is disconnected. Serializing a sample costs only while someone is subscribed to it.
#include "live/scene_outlet.hpp"

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::fw {

struct LiveOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;               // 0: any free port (port() says which)
  std::size_t max_queue = 8u << 20;        // bytes queued per client before samples are dropped
  std::size_t max_request = 64u << 10;     // bytes of one client message
  int max_requests_per_s = 200;            // client messages a second before it is disconnected
  bool sim_clock = false;                  // send the run's time (capability "time")
  // A point-cloud channel sends at most this many clouds a second of wall time (0: every one):
  // a display shows no more, and a sim run at 18x real time would otherwise push its three
  // LiDARs' 20 Hz as 1,000 clouds a second through the socket. At --pace 1 nothing is left out.
  double cloud_hz = 20;
  std::string name = "brickyard";
};

struct LiveStats {
  std::uint64_t clients = 0, sent = 0, dropped = 0, refused_requests = 0, disconnected = 0;
  std::uint64_t clouds_thinned = 0;  // clouds not sent: a channel's cloud_hz would be exceeded
  double server_cpu_s = 0;           // the server thread's CPU time so far (its own share of the run's cost)
};

class LiveServer : public SceneOutlet {
 public:
  // Binds and listens; throws std::runtime_error naming address:port when it cannot.
  explicit LiveServer(LiveOptions opt);
  ~LiveServer();  // closes every connection and joins the thread
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  std::uint16_t port() const;
  // A channel (before start()): its id for publish(). `cloud`: its samples are point clouds, sent
  // at most at LiveOptions::cloud_hz.
  std::uint32_t add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                            const std::string& schema_encoding, const std::string& schema, bool cloud = false) override;
  void start();  // serves from here on, on its own thread

  // Whether any client is subscribed to the channel and, for a cloud channel, a cloud is due
  // (cheap: check before serializing).
  bool wanted(std::uint32_t channel) const override;
  // One sample to every client subscribed to its channel; never blocks on a client.
  void publish(std::uint32_t channel, std::uint64_t stamp_ns, const unsigned char* data, std::size_t size) override;
  // The run's time (sim clock), sent when it has moved on by `every_ns` since the last.
  void time(std::uint64_t stamp_ns, std::uint64_t every_ns = 10'000'000);
  LiveStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace brickyard::fw
