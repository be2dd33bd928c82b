// testing.json_source: publishes samples of any message type written as JSON — inline or in a
// file — each at its time, on the type of the input it is wired to: a planner, a controller or
// the fusion tested without the simulator (docs/testing.md).
#include <brickyard/plugin.hpp>

#include "json_samples.hpp"

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

namespace {

using namespace brickyard;

constexpr std::uintmax_t kMaxFileBytes = 256u << 20;

struct Settings {
  std::string samples = "[]";
  std::string file;
  std::string type;
  double rate_hz = 100;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind_json("samples", &Settings::samples).doc("[{\"t\": SECONDS, \"msg\": {...}}, ...]: each message as JSON, at its time");
  b.bind("file", &Settings::file).doc("a JSON file of such samples instead (relative to the graph)");
  b.bind("type", &Settings::type)
      .doc("the message type (brickyard::msgs::VehicleState); empty: the type of the input it feeds. Needed when it feeds only "
           "inputs of any type (a testing.expect's ref)");
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(0.1, 10000).doc("how often due samples are sent");
  return b;
}

// Named once: check() asks the validator about the same port.
constexpr char kOut[] = "out";

struct Ports {
  AnyOutput out;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.output(kOut, &Ports::out).doc("the samples: the type parameter's, or that of the input this is wired to").type_from("type");
  return b;
}

class JsonSource : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.json_source", "1.0.0")
        .describe("publishes samples of any message type written as JSON, each at its time, as the type of the input it feeds")
        .with_ports(ports())
        .parameters(bindings())
        .periodic("rate_hz")
        .check(&JsonSource::check);
  }

  void configure(Context& ctx) override {
    io_ = ports().connect(ctx);
    samples_ = load(bindings().read(ctx.params()), io_.out.type_name(), io_.out.idl(),
                    [&](const std::string& f) { return ctx.find_file(f); });
  }

  // At validation: the script read and encoded as configure will, on the type the wire carries.
  static void check(const CheckView& v) {
    load(bindings().read(v.params()), v.port_type(kOut), v.port_idl(kOut), [&](const std::string& f) { return v.find_file(f); });
  }

  void step(Context& ctx) override {
    for (; next_ < samples_.size() && samples_[next_].t_ns <= ctx.now_ns(); ++next_)
      io_.out.publish(SerializedSample{samples_[next_].cdr});
  }

  void deactivate(Context& ctx) override {
    ctx.metric("published", static_cast<double>(next_));
    ctx.metric("left", static_cast<double>(samples_.size() - next_));
  }

 private:
  template <class FindFile>
  static std::vector<testing::ScriptedSample> load(const Settings& s, const std::string& type, const char* idl_text,
                                                   FindFile find_file) {
    if (type.empty())
      throw BadInput(std::string("output '") + kOut + "' feeds no input: it takes its readers' type, so it needs one");
    const cdr::CdrJson idl(idl_text ? idl_text : "");
    const bool inline_given = s.samples != "[]";
    if (inline_given == !s.file.empty()) throw BadInput("parameter 'samples': give samples or file, one of them");
    std::string where = "parameter 'samples' ";
    try {
      nlohmann::json script;
      if (inline_given) {
        script = nlohmann::json::parse(s.samples);
      } else {
        const std::string path = find_file(s.file);
        where = "file " + path + ": ";
        // Of a sane size (find_file has refused what is not a regular file): a runaway script.
        std::error_code ec;
        if (std::filesystem::file_size(path, ec) > kMaxFileBytes)
          throw BadInput(where + "larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
        std::ifstream f(path);
        std::stringstream text;
        text << f.rdbuf();
        if (!f) throw BadInput(where + "cannot be read");
        script = nlohmann::json::parse(text.str());
      }
      return testing::encode_script(script, idl, type);
    } catch (const std::invalid_argument& e) {
      throw BadInput(where + e.what() + " (" + type + ")");
    } catch (const nlohmann::json::exception& e) {
      throw BadInput(where + e.what());
    }
  }

  Ports io_;
  std::vector<testing::ScriptedSample> samples_;
  std::size_t next_ = 0;
};

}  // namespace

BRICKYARD_PLUGINS(JsonSource)
