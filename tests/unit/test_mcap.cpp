// The MCAP container (libs/mcap): what the writer writes the reader reads back, in every
// compression; damage of every kind is found, named by its byte offset, and what came before it
// is kept. (Foxglove's own reader judges the files in evidence.mcap_recording.)
#include "mcap/mcap_reader.hpp"
#include "mcap/mcap_writer.hpp"
#include "record/recorder.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

using namespace brickyard::mcap;

namespace {

std::string temp(const std::string& name) {
  const std::string p = testing::TempDir() + name;
  std::remove(p.c_str());
  return p;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

void spit(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// Two channels, 3000 messages of 8 to 40 bytes at 1 ms, chunks of 16 KiB.
void write_sample(const std::string& path, Compression c) {
  WriterOptions o;
  o.compression = c;
  o.chunk_size = 16 << 10;
  Writer w(path, o);
  w.add_metadata("brickyard", {{"clock", "sim"}, {"seed", "7"}});
  const auto s = w.add_schema("t::A", "omgidl", "module t { struct A { double x; }; };");
  const auto a = w.add_channel(s, "a.out", "cdr", {{"type_hash", "h"}});
  const auto b = w.add_channel(s, "b.out", "cdr");
  for (int i = 0; i < 3000; ++i) {
    std::string d(8 + i % 33, static_cast<char>(i));
    w.write(i % 4 ? a : b, static_cast<std::uint64_t>(i) * 1000000, static_cast<std::uint64_t>(i) * 1000000, d.data(), d.size());
  }
  w.close();
}

}  // namespace

TEST(Mcap, WhatIsWrittenIsReadBackInEveryCompression) {
  for (Compression c : {Compression::Zstd, Compression::Lz4, Compression::None}) {
    const std::string path = temp("round_trip.mcap");
    write_sample(path, c);
    Reader r(path);
    EXPECT_EQ(r.damage(), nullptr) << r.damage()->what;
    ASSERT_EQ(r.channels().size(), 2u);
    const ChannelInfo* a = r.channel("a.out");
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->messages, 2250u);
    EXPECT_EQ(a->metadata.at("type_hash"), "h");
    EXPECT_EQ(r.schemas().at(a->schema).name, "t::A");
    EXPECT_EQ(r.metadata().at("brickyard").at("seed"), "7");
    int i = 0;
    bool same = true;
    const std::set<std::uint16_t> only{a->id};
    r.read([&](const MessageView& m) {
      while (i % 4 == 0) ++i;  // only a.out's: every message but each fourth
      same = same && m.log_time == static_cast<std::uint64_t>(i) * 1000000 && m.size == static_cast<std::size_t>(8 + i % 33) &&
             m.data[0] == static_cast<unsigned char>(i);
      ++i;
    }, &only);
    EXPECT_TRUE(same);
    EXPECT_EQ(i, 3000);
  }
}

TEST(Mcap, AFileCutShortIsReadUpToTheCutAndSaysWhere) {
  const std::string path = temp("whole.mcap"), cut = temp("cut.mcap");
  write_sample(path, Compression::Zstd);
  const std::string bytes = slurp(path);
  spit(cut, bytes.substr(0, bytes.size() / 2));
  Reader r(cut);
  ASSERT_NE(r.damage(), nullptr);
  EXPECT_NE(r.damage()->what.find("runs past the end of the file"), std::string::npos) << r.damage()->what;
  EXPECT_LT(r.damage()->offset, bytes.size() / 2);
  const std::uint64_t kept = r.channel("a.out")->messages + r.channel("b.out")->messages;
  EXPECT_GT(kept, 500u);  // the whole chunks before the cut
  EXPECT_LT(kept, 3000u);
}

TEST(Mcap, AChunkWhoseBytesChangedIsDamage) {
  const std::string path = temp("whole2.mcap"), bad = temp("flipped.mcap");
  for (Compression c : {Compression::Zstd, Compression::None}) {
    std::remove(path.c_str());
    write_sample(path, c);
    std::string bytes = slurp(path);
    for (std::size_t i = bytes.size() / 3; i < bytes.size() / 3 + 16; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
    std::remove(bad.c_str());
    spit(bad, bytes);
    Reader r(bad);
    ASSERT_NE(r.damage(), nullptr);
    EXPECT_GT(r.damage()->offset, 0u);
  }
}

TEST(Mcap, AFileWithoutItsFooterWasNotClosed) {
  const std::string path = temp("open.mcap");
  {
    Writer w(path);
    const auto c = w.add_channel(0, "a", "cdr");
    w.write(c, 1, 1, "abcd", 4);
    w.flush();
    // Read while the writer still holds it: what a killed run leaves.
    Reader r(path);
    ASSERT_NE(r.damage(), nullptr);
    EXPECT_NE(r.damage()->what.find("was not closed"), std::string::npos) << r.damage()->what;
    EXPECT_EQ(r.channel("a")->messages, 1u);
  }
}

TEST(Mcap, ALengthThatClaimsMoreThanTheFileIsNotAnAllocation) {
  const std::string path = temp("huge.mcap");
  std::string bytes(reinterpret_cast<const char*>(kMagic), sizeof kMagic);
  bytes += '\x01';  // a Header claiming 2^62 bytes
  const std::uint64_t len = 1ull << 62;
  bytes.append(reinterpret_cast<const char*>(&len), 8);
  spit(path, bytes);
  Reader r(path);
  ASSERT_NE(r.damage(), nullptr);
  EXPECT_EQ(r.damage()->offset, 8u);
  spit(temp("not.mcap"), "not an mcap file at all");
  EXPECT_THROW(Reader(testing::TempDir() + "not.mcap"), ReadError);
  EXPECT_THROW(Reader(testing::TempDir() + "nothing_here.mcap"), ReadError);
}

TEST(Mcap, AnExistingFileIsNeverReplaced) {
  const std::string path = temp("exists.mcap");
  spit(path, "keep me");
  EXPECT_THROW(Writer w(path), std::runtime_error);
  EXPECT_EQ(slurp(path), "keep me");
}

// The schema Foxglove parses: no #include, each included definition once, before its users.
TEST(Mcap, TheSchemaIsOneSelfContainedIdl) {
  const std::string idl = brickyard::fw::omgidl_schema(brickyard::fw::idl_text("brickyard::msgs::LocalizationEstimate"));
  EXPECT_EQ(idl.find("#include"), std::string::npos);
  const auto header = idl.find("struct Header"), estimate = idl.find("struct LocalizationEstimate");
  ASSERT_NE(header, std::string::npos);
  ASSERT_NE(estimate, std::string::npos);
  EXPECT_LT(header, estimate);
  EXPECT_EQ(idl.find("struct Header", header + 1), std::string::npos);
}

TEST(Mcap, ASchemaWithTwoIncludesDefinesBothBeforeItsType) {
  const std::string idl = brickyard::fw::omgidl_schema(brickyard::fw::idl_text("brickyard::msgs::Path"));
  const auto path = idl.find("struct Path");
  ASSERT_NE(path, std::string::npos);
  EXPECT_LT(idl.find("struct Header"), path);
  EXPECT_LT(idl.find("struct Pose2D"), path);
}
