#include "live/live_server.hpp"

// websocketpp on standalone asio (Debian's libwebsocketpp-dev and libasio-dev), no TLS: the
// server binds loopback unless a graph or flag says otherwise.
#define ASIO_STANDALONE
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <condition_variable>
#include <cstring>
#include <ctime>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include <pthread.h>  // pthread_getcpuclockid: the server thread's CPU time

namespace brickyard::fw {

namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;
constexpr const char* kSubprotocol = "foxglove.websocket.v1";

struct Channel {
  std::string topic, encoding, schema_name, schema_encoding, schema;
  bool cloud = false;
};

std::int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// One connected client. `subs` (subscription id → channel) lives on the server's thread; the
// rest is shared with the publishing threads under `m`.
struct Client {
  Hdl hdl;
  std::map<std::uint32_t, std::uint32_t> subs;
  std::chrono::steady_clock::time_point window;
  int requests = 0;
  std::mutex m;
  std::unordered_map<std::uint32_t, std::uint32_t> by_channel;  // channel → subscription id
  // What the run published for this client since the last drain: whole WebSocket frames, one
  // after another (frame_header), sent as one prepared message (drain).
  std::string pending;
  std::size_t pending_frames = 0;
};

// A server's unmasked, final binary frame of n payload bytes: its header (RFC 6455 §5.2).
void frame_header(std::string& out, std::size_t n) {
  out.push_back(static_cast<char>(0x82));
  if (n < 126) {
    out.push_back(static_cast<char>(n));
  } else if (n <= 0xffff) {
    out.push_back(126);
    out.push_back(static_cast<char>(n >> 8));
    out.push_back(static_cast<char>(n & 0xff));
  } else {
    out.push_back(127);
    for (int shift = 56; shift >= 0; shift -= 8) out.push_back(static_cast<char>((static_cast<std::uint64_t>(n) >> shift) & 0xff));
  }
}
}  // namespace

struct LiveServer::Impl {
  LiveOptions opt;
  Server server;
  std::thread thread;
  std::vector<Channel> channels;
  std::unique_ptr<std::atomic<int>[]> subscribers;  // per channel: how many clients are subscribed
  std::unique_ptr<std::atomic<std::int64_t>[]> next_cloud_ns;  // per channel: a cloud channel's next send, wall time
  std::mutex clients_m;
  std::condition_variable clients_cv;
  std::map<Hdl, std::shared_ptr<Client>, std::owner_less<Hdl>> clients;
  std::atomic<std::uint64_t> sent{0}, dropped{0}, refused{0}, disconnected{0}, accepted{0}, thinned{0};
  std::atomic<std::uint64_t> last_time{0};
  std::atomic<bool> any_time{false};
  bool started = false;
  std::unique_ptr<asio::steady_timer> timer;

  void send_json(Hdl h, const nlohmann::json& j) {
    websocketpp::lib::error_code ec;
    server.send(h, j.dump(), websocketpp::frame::opcode::text, ec);
  }
  void status(Hdl h, int level, const std::string& message) {
    send_json(h, {{"op", "status"}, {"level", level}, {"message", message}});
  }
  std::shared_ptr<Client> client(Hdl h) {
    std::lock_guard<std::mutex> l(clients_m);
    auto it = clients.find(h);
    return it == clients.end() ? nullptr : it->second;
  }
  // Appends one Foxglove binary message (opcode, then `head` bytes, then `body`) to a client's
  // pending frames, or counts it dropped when they would pass max_queue. Called with c->m held.
  void append(Client& c, unsigned char opcode, const void* head, std::size_t head_size, const void* body, std::size_t body_size) {
    const std::size_t n = 1 + head_size + body_size;
    if (c.pending.size() + n + 10 > opt.max_queue) {
      ++dropped;
      return;
    }
    frame_header(c.pending, n);
    c.pending.push_back(static_cast<char>(opcode));
    c.pending.append(static_cast<const char*>(head), head_size);
    if (body_size) c.pending.append(static_cast<const char*>(body), body_size);
    ++c.pending_frames;
  }
  // Every 2 ms the server's thread writes what the run queued: a wake-up per sample cost more
  // than the samples (futex and epoll calls, one socket write per few frames).
  void tick() {
    std::vector<std::shared_ptr<Client>> all;
    {
      std::lock_guard<std::mutex> l(clients_m);
      for (const auto& [h, c] : clients) all.push_back(c);
    }
    for (const auto& c : all) drain(c);
    timer->expires_after(std::chrono::milliseconds(2));
    timer->async_wait([this](const asio::error_code& ec) {
      if (!ec) tick();
    });
  }
  // A client's pending frames go out as one message that websocketpp writes as it is (prepared:
  // the frames already framed): one message, one allocation and one write for the hundreds of
  // frames a run publishes in 2 ms, where a send per frame cost 2.9 µs of the server's thread
  // each (docs/live.md).
  void drain(const std::shared_ptr<Client>& c) {
    std::string frames;
    std::size_t count = 0;
    {
      std::lock_guard<std::mutex> l(c->m);
      if (c->pending.empty()) return;
      frames.swap(c->pending);
      count = c->pending_frames;
      c->pending_frames = 0;
      c->pending.reserve(frames.size());  // the last batch's size, not a capacity one burst of clouds ratcheted up
    }
    websocketpp::lib::error_code ec;
    auto con = server.get_con_from_hdl(c->hdl, ec);
    if (ec || con->get_state() != websocketpp::session::state::open) return;
    // What the socket has not taken yet: a client that does not read loses samples.
    if (con->get_buffered_amount() > opt.max_queue) {
      dropped += count;
      return;
    }
    auto msg = con->get_message(websocketpp::frame::opcode::binary, 0);
    msg->get_raw_payload().swap(frames);
    msg->set_header("");
    msg->set_prepared(true);
    if (!con->send(msg)) sent += count;
  }
  void on_open(Hdl h) {
    auto c = std::make_shared<Client>();
    c->hdl = h;
    c->window = std::chrono::steady_clock::now();
    {
      std::lock_guard<std::mutex> l(clients_m);
      clients[h] = c;
    }
    ++accepted;
    nlohmann::json info = {{"op", "serverInfo"}, {"name", opt.name}, {"capabilities", nlohmann::json::array()},
                           {"metadata", {{"clock", opt.sim_clock ? "sim" : "real"}}}};
    if (opt.sim_clock) info["capabilities"].push_back("time");
    send_json(h, info);
    nlohmann::json adv = {{"op", "advertise"}, {"channels", nlohmann::json::array()}};
    for (std::size_t i = 0; i < channels.size(); ++i) {
      const Channel& ch = channels[i];
      adv["channels"].push_back({{"id", i + 1}, {"topic", ch.topic}, {"encoding", ch.encoding}, {"schemaName", ch.schema_name},
                                 {"schemaEncoding", ch.schema_encoding}, {"schema", ch.schema}});
    }
    send_json(h, adv);
  }
  void on_close(Hdl h) {
    std::shared_ptr<Client> c;
    {
      std::lock_guard<std::mutex> l(clients_m);
      auto it = clients.find(h);
      if (it == clients.end()) return;
      c = it->second;
      clients.erase(it);
    }
    std::lock_guard<std::mutex> l(c->m);
    for (const auto& [channel, id] : c->by_channel) --subscribers[channel];
    c->by_channel.clear();
    clients_cv.notify_all();
  }
  void on_message(Hdl h, Server::message_ptr msg) {
    auto c = client(h);
    if (!c) return;
    // A client that floods requests is disconnected: it must not take the server's thread.
    const auto now = std::chrono::steady_clock::now();
    if (now - c->window > std::chrono::seconds(1)) c->window = now, c->requests = 0;
    if (++c->requests > opt.max_requests_per_s) {
      ++refused;
      ++disconnected;
      websocketpp::lib::error_code ec;
      server.close(h, websocketpp::close::status::policy_violation, "too many requests", ec);
      return;
    }
    if (msg->get_opcode() != websocketpp::frame::opcode::text) {
      ++refused;
      return status(h, 2, "binary messages (client publishing) are not supported");
    }
    const auto j = nlohmann::json::parse(msg->get_payload(), nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("op") || !j["op"].is_string()) {
      ++refused;
      return status(h, 2, "not a JSON object with an \"op\"");
    }
    const std::string op = j["op"];
    if (op == "subscribe") {
      if (!j.contains("subscriptions") || !j["subscriptions"].is_array()) return status(h, 2, "subscribe: no \"subscriptions\" array");
      for (const auto& s : j["subscriptions"]) {
        if (!s.is_object() || !s.contains("id") || !s.contains("channelId") || !s["id"].is_number_unsigned() ||
            !s["channelId"].is_number_unsigned() || s["id"].get<std::uint64_t>() > 0xffffffffu) {
          ++refused;
          status(h, 2, "subscribe: each subscription needs an \"id\" and a \"channelId\" (unsigned integers)");
          continue;
        }
        const auto id = s["id"].get<std::uint32_t>();
        const auto ch = s["channelId"].get<std::uint64_t>();
        if (ch < 1 || ch > channels.size()) {
          ++refused;
          status(h, 1, "subscribe: no channel " + std::to_string(ch));
          continue;
        }
        const auto channel = static_cast<std::uint32_t>(ch - 1);
        std::lock_guard<std::mutex> l(c->m);
        if (c->subs.count(id) || c->by_channel.count(channel)) {
          ++refused;
          status(h, 1, "subscribe: subscription " + std::to_string(id) + " or channel " + std::to_string(ch) + " is already subscribed");
          continue;
        }
        c->subs[id] = channel;
        c->by_channel[channel] = id;
        ++subscribers[channel];
      }
    } else if (op == "unsubscribe") {
      if (!j.contains("subscriptionIds") || !j["subscriptionIds"].is_array()) return status(h, 2, "unsubscribe: no \"subscriptionIds\" array");
      for (const auto& s : j["subscriptionIds"]) {
        if (!s.is_number_unsigned() || s.get<std::uint64_t>() > 0xffffffffu) continue;
        std::lock_guard<std::mutex> l(c->m);
        auto it = c->subs.find(s.get<std::uint32_t>());
        if (it == c->subs.end()) continue;
        c->by_channel.erase(it->second);
        --subscribers[it->second];
        c->subs.erase(it);
      }
    } else {
      ++refused;
      status(h, 1, "op \"" + op + "\" is not supported by this server");
    }
  }
};

LiveServer::LiveServer(LiveOptions opt) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.opt = std::move(opt);
  s.server.clear_access_channels(websocketpp::log::alevel::all);
  s.server.clear_error_channels(websocketpp::log::elevel::all);
  s.server.set_max_message_size(s.opt.max_request);
  s.server.set_close_handshake_timeout(500);
  s.server.set_open_handshake_timeout(2000);
  const std::string where = s.opt.address + ":" + std::to_string(s.opt.port);
  try {
    s.server.init_asio();
    s.server.set_reuse_addr(true);
    s.server.set_validate_handler([this](Hdl h) {
      websocketpp::lib::error_code ec;
      auto con = impl_->server.get_con_from_hdl(h, ec);
      if (ec) return false;
      for (const auto& p : con->get_requested_subprotocols())
        if (p == kSubprotocol) {
          con->select_subprotocol(kSubprotocol, ec);
          return !ec;
        }
      return false;  // not a Foxglove client
    });
    s.server.set_open_handler([this](Hdl h) { impl_->on_open(h); });
    s.server.set_close_handler([this](Hdl h) { impl_->on_close(h); });
    s.server.set_fail_handler([this](Hdl h) { impl_->on_close(h); });
    s.server.set_message_handler([this](Hdl h, Server::message_ptr m) {
      try {
        impl_->on_message(h, std::move(m));
      } catch (const std::exception&) {  // a reply to a client that has gone: nothing to do
      }
    });
    asio::error_code ec;
    const auto address = asio::ip::make_address(s.opt.address, ec);
    if (ec) throw std::runtime_error("not an IP address");
    s.server.listen(asio::ip::tcp::endpoint(address, s.opt.port));
    s.server.start_accept();
  } catch (const websocketpp::exception& e) {
    throw std::runtime_error("--live " + where + ": cannot listen (" + e.what() + ")");
  } catch (const std::exception& e) {
    throw std::runtime_error("--live " + where + ": cannot listen (" + e.what() + ")");
  }
}

LiveServer::~LiveServer() {
  Impl& s = *impl_;
  if (!s.started) return;
  // Stop accepting, close every client (a client that does not answer is dropped after the
  // close handshake's 0.5 s), then stop the loop.
  asio::post(s.server.get_io_service(), [&s] {
    websocketpp::lib::error_code ec;
    s.server.stop_listening(ec);
    s.timer->cancel();
    std::vector<Hdl> hs;
    std::vector<std::shared_ptr<Client>> all;
    {
      std::lock_guard<std::mutex> l(s.clients_m);
      for (const auto& [h, c] : s.clients) hs.push_back(h), all.push_back(c);
    }
    for (const auto& c : all) s.drain(c);  // what the run published last goes out before the close
    for (const auto& h : hs) s.server.close(h, websocketpp::close::status::going_away, "the run ended", ec);
  });
  {
    std::unique_lock<std::mutex> l(s.clients_m);
    s.clients_cv.wait_for(l, std::chrono::seconds(1), [&s] { return s.clients.empty(); });
  }
  s.server.stop();
  if (s.thread.joinable()) s.thread.join();
}

std::uint16_t LiveServer::port() const {
  asio::error_code ec;
  const auto ep = impl_->server.get_local_endpoint(ec);
  return ec ? 0 : ep.port();
}

std::uint32_t LiveServer::add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                                      const std::string& schema_encoding, const std::string& schema, bool cloud) {
  impl_->channels.push_back({topic, encoding, schema_name, schema_encoding, schema, cloud});
  return static_cast<std::uint32_t>(impl_->channels.size() - 1);
}

void LiveServer::start() {
  Impl& s = *impl_;
  s.subscribers = std::make_unique<std::atomic<int>[]>(s.channels.size() + 1);
  for (std::size_t i = 0; i <= s.channels.size(); ++i) s.subscribers[i] = 0;
  s.next_cloud_ns = std::make_unique<std::atomic<std::int64_t>[]>(s.channels.size() + 1);
  for (std::size_t i = 0; i <= s.channels.size(); ++i) s.next_cloud_ns[i] = 0;
  s.started = true;
  s.timer = std::make_unique<asio::steady_timer>(s.server.get_io_service());
  asio::post(s.server.get_io_service(), [&s] { s.tick(); });
  s.thread = std::thread([&s] {
    try {
      s.server.run();
    } catch (const std::exception&) {  // the loop ends with the run; nothing is left to serve
    }
  });
}

bool LiveServer::wanted(std::uint32_t channel) const {
  Impl& s = *impl_;
  if (!s.started || channel >= s.channels.size() || s.subscribers[channel].load(std::memory_order_relaxed) <= 0) return false;
  // A cloud channel takes a cloud when its interval has passed (one writer per channel: the node
  // that publishes it, so the check and the publish after it do not race).
  if (s.channels[channel].cloud && s.opt.cloud_hz > 0 && steady_ns() < s.next_cloud_ns[channel].load(std::memory_order_relaxed)) {
    ++s.thinned;
    return false;
  }
  return true;
}

void LiveServer::publish(std::uint32_t channel, std::uint64_t stamp_ns, const unsigned char* data, std::size_t size) {
  if (!wanted(channel)) return;
  Impl& s = *impl_;
  if (s.channels[channel].cloud && s.opt.cloud_hz > 0)
    s.next_cloud_ns[channel].store(steady_ns() + static_cast<std::int64_t>(1e9 / s.opt.cloud_hz), std::memory_order_relaxed);
  // Message Data: opcode 1, subscription id (u32), receive time (u64), the payload.
  std::lock_guard<std::mutex> all(s.clients_m);
  for (const auto& [h, c] : s.clients) {
    std::lock_guard<std::mutex> l(c->m);
    auto it = c->by_channel.find(channel);
    if (it == c->by_channel.end()) continue;
    unsigned char head[12];
    std::memcpy(head, &it->second, 4);
    std::memcpy(head + 4, &stamp_ns, 8);
    s.append(*c, 0x01, head, sizeof head, data, size);
  }
}

void LiveServer::time(std::uint64_t stamp_ns, std::uint64_t every_ns) {
  Impl& s = *impl_;
  if (!s.started || !s.opt.sim_clock) return;
  if (s.any_time.load() && stamp_ns < s.last_time.load() + every_ns) return;
  s.any_time = true;
  s.last_time = stamp_ns;
  // Time: opcode 2, the time (u64).
  std::lock_guard<std::mutex> all(s.clients_m);
  for (const auto& [h, c] : s.clients) {
    std::lock_guard<std::mutex> l(c->m);
    s.append(*c, 0x02, &stamp_ns, 8, nullptr, 0);
  }
}

LiveStats LiveServer::stats() const {
  const Impl& s = *impl_;
  double cpu = 0;
  clockid_t id;
  timespec ts{};
  if (s.thread.joinable() && pthread_getcpuclockid(const_cast<std::thread&>(s.thread).native_handle(), &id) == 0 &&
      clock_gettime(id, &ts) == 0)
    cpu = static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  return {s.accepted.load(), s.sent.load(), s.dropped.load(), s.refused.load(), s.disconnected.load(), s.thinned.load(), cpu};
}

}  // namespace brickyard::fw
