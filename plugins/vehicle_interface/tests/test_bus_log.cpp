// The bus's record (common/bus_log.hpp): each frame kept as it went, named by the DBC's message and
// decoded into its signals; a frame the DBC does not know is kept raw, one that does not decode is
// counted.
#include "vehicle_interface/common/bus_log.hpp"
#include "vehicle_interface/common/dbc_reader.hpp"

#include <gtest/gtest.h>

using namespace brickyard::vehicle_interface;

namespace {
DbcDatabase car_dbc() {
  DbcReadResult read = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  return std::move(*read.database);
}
}  // namespace

TEST(BusLog, KeepsEachFrameNamedAndDecoded) {
  const DbcDatabase db = car_dbc();
  const DbcMessage* steering = db.find("steering_cmd");
  ASSERT_NE(steering, nullptr);
  const PackResult p = pack_message(*steering, {{"steering_motor_ang_cmd", -12.5}, {"steering_motor_cmd_counter", 7}});
  ASSERT_TRUE(p.ok());
  CanFrame unknown;
  unknown.id = 0x7AB, unknown.length = 2, unknown.data[0] = 0xDE, unknown.data[1] = 0xAD;
  CanFrame short_frame = p.frame;
  short_frame.length = 1;  // steering_cmd is 8 bytes
  BusLog log(db, true);
  log.add({p.frame, unknown}, 1'000'000, true);
  log.add({short_frame}, 2'000'000, false);
  ASSERT_EQ(log.frames().size(), 3u);
  const LoggedFrame& a = log.frames()[0];
  EXPECT_TRUE(a.sent);
  EXPECT_EQ(a.stamp_ns, 1'000'000);
  EXPECT_EQ(a.frame, p.frame);
  ASSERT_NE(a.message, nullptr);
  EXPECT_EQ(a.message->name, "steering_cmd");
  EXPECT_DOUBLE_EQ(a.signals.at("steering_motor_ang_cmd"), -12.5);
  EXPECT_DOUBLE_EQ(a.signals.at("steering_motor_cmd_counter"), 7);
  EXPECT_EQ(log.frames()[1].message, nullptr);  // no message of that id: raw
  EXPECT_TRUE(log.frames()[1].signals.empty());
  EXPECT_FALSE(log.frames()[2].sent);
  EXPECT_TRUE(log.frames()[2].signals.empty());
  EXPECT_EQ(log.undecoded(), 1u);
  log.clear();
  EXPECT_TRUE(log.frames().empty());
  BusLog raw(db, false);
  raw.add({p.frame}, 0, true);
  EXPECT_EQ(raw.frames()[0].message->name, "steering_cmd");
  EXPECT_TRUE(raw.frames()[0].signals.empty());
}
