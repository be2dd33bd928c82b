#pragma once
// sim.ouster's parameters (plugin.cpp), read the same way at validation and in configure: the
// sensor's metadata read and the sink parsed (not opened: that is configure's). Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "drivers/io/byte_source.hpp"
#include "drivers/ouster_metadata_param.hpp"
#include "sim/common/ouster_emulator.hpp"
#include "vehicle_param.hpp"

#include <string>
#include <vector>

namespace brickyard::sim {

struct Settings {
  std::string metadata, sink;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount, mount_rpy_deg;  // empty: the vehicle file's mount
  OusterEmulatorParams sensor;
};

inline ParamBinding<Settings> bindings() {
  using P = OusterEmulatorParams;
  ParamBinding<Settings> b;
  b.bind_required("metadata", &Settings::metadata).doc("the sensor's metadata JSON: its beams, columns, profile and rate");
  b.bind_required("sink", &Settings::sink).doc("where the packets go: udp://HOST:PORT (the driver's source)");
  b.declare(ParamSpec::number("rate_hz", 2000).in_unit("Hz").range(10, 100000)
                .doc("how often the packets due are sent (the sensor sends one each 1/640 s at 1024x10): at least the packet rate"));
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its LiDARs sit");
  b.bind("vehicle_mount", &Settings::vehicle_mount).doc("the sensor's mount in the vehicle file");
  b.bind("mount", &Settings::mount).in_unit("m").range(-100, 100).doc("sensor position in base_link, m (x, y, z); empty: vehicle_mount's");
  b.bind("mount_rpy_deg", &Settings::mount_rpy_deg).in_unit("deg").range(-360, 360).doc("sensor roll, pitch, yaw, deg; empty: vehicle_mount's");
  b.bind("range_noise", &Settings::sensor, &P::range_noise).in_unit("m").range(0, 10).doc("1 sigma");
  b.bind("dropout", &Settings::sensor, &P::dropout).range(0, 1).doc("probability that a return is lost");
  b.bind("min_range", &Settings::sensor, &P::min_range).in_unit("m").range(0, 100);
  b.bind("max_range", &Settings::sensor, &P::max_range).in_unit("m").range(1, 1000);
  b.below("min_range", "max_range");
  return b;
}

template <class Files> drivers::OusterMetadata read_setup(const Files& files, const Settings& s) {
  if (const drivers::ParsedSource p = drivers::parse_source(s.sink); !p.spec || p.spec->kind != drivers::SourceSpec::Kind::udp)
    throw BadInput("parameter 'sink': " + (p.spec ? s.sink + ": an Ouster sends to udp://HOST:PORT" : p.error));
  return drivers::read_ouster_metadata_param(files, s.metadata, "metadata");
}

inline void check(const CheckView& v) {
  const Settings s = bindings().read(v.params());
  plugins::check_vehicle_file<&bindings, &Settings::vehicle>(v);
  read_setup(v, s);
}

}  // namespace brickyard::sim
