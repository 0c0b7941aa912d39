#include "asbuilt/formats/safetensors.h"

#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

SafeTensor F32(std::vector<std::int64_t> shape, std::vector<float> values) {
  SafeTensor t;
  t.dtype = "F32";
  t.shape = std::move(shape);
  t.data.resize(values.size() * 4);
  std::memcpy(t.data.data(), values.data(), t.data.size());
  return t;
}

std::string Header(const std::string& json, const std::string& data) {
  std::string out(8, '\0');
  for (int i = 0; i < 8; ++i) out[i] = static_cast<char>((json.size() >> (8 * i)) & 0xff);
  return out + json + data;
}

std::string MessageOf(const std::string& bytes) {
  try {
    ParseSafeTensors(bytes, "w.safetensors");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SafeTensors, RoundTripsTensorsAndMetadata) {
  SafeTensorsFile f;
  f.tensors["b.weight"] = F32({2, 3}, {1, 2, 3, 4, 5, 6});
  f.tensors["a.bias"] = F32({3}, {-1, 0.5f, 7});
  SafeTensor count;
  count.dtype = "I64";
  count.shape = {};
  count.data = std::string("\x05\0\0\0\0\0\0\0", 8);
  f.tensors["n"] = count;
  f.metadata["asbuilt_meta"] = R"({"format":"x"})";
  const std::string bytes = SerializeSafeTensors(f);
  EXPECT_EQ((bytes.size() - 8 - 4 * 9 - 8) % 8, 0u) << "header padded to 8 bytes";
  SafeTensorsFile g = ParseSafeTensors(bytes, "mem");
  ASSERT_EQ(g.tensors.size(), 3u);
  EXPECT_EQ(g.tensors["b.weight"].shape, (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(g.tensors["b.weight"].data, f.tensors["b.weight"].data);
  EXPECT_EQ(g.tensors["a.bias"].data, f.tensors["a.bias"].data);
  EXPECT_EQ(g.tensors["n"].numel(), 1);
  EXPECT_EQ(g.metadata, f.metadata);
}

TEST(SafeTensors, ReadsAFileWrittenByTheReferenceLayout) {
  // Hand-made file as the Python package writes it: one F32 [2] tensor.
  std::string data(8, '\0');
  float v[2] = {1.5f, -2.0f};
  std::memcpy(data.data(), v, 8);
  SafeTensorsFile f =
      ParseSafeTensors(Header(R"({"x":{"dtype":"F32","shape":[2],"data_offsets":[0,8]}})", data), "mem");
  float back[2];
  std::memcpy(back, f.tensors.at("x").data.data(), 8);
  EXPECT_EQ(back[0], 1.5f);
  EXPECT_EQ(back[1], -2.0f);
}

TEST(SafeTensors, RejectsInconsistentFilesNamingTheField) {
  const std::string d8(8, '\0');
  EXPECT_NE(MessageOf("abc").find("too short"), std::string::npos);
  EXPECT_NE(MessageOf(std::string("\xff\xff\0\0\0\0\0\0", 8) + "{}").find("header length"), std::string::npos);
  EXPECT_NE(MessageOf(Header("[1]", "")).find("not a JSON object"), std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F99","shape":[2],"data_offsets":[0,8]}})", d8)).find("x.dtype"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[-2],"data_offsets":[0,8]}})", d8)).find("x.shape"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[3],"data_offsets":[0,8]}})", d8)).find("x.data_offsets"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[2],"data_offsets":[0,16]}})", d8)).find("outside"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[1],"data_offsets":[0,4]},)"
                             R"("y":{"dtype":"F32","shape":[1],"data_offsets":[0,4]}})",
                             d8))
                .find("overlaps"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[1],"data_offsets":[0,4]}})", d8)).find("after the last"),
            std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"__metadata__":{"k":1}})", "")).find("__metadata__.k"), std::string::npos);
  EXPECT_NE(MessageOf(Header(R"({"x":{"dtype":"F32","shape":[4294967295,4294967295],"data_offsets":[0,8]}})", d8))
                .find("too many"),
            std::string::npos);
}

TEST(SafeTensors, SerializeRejectsDataThatDoesNotMatchTheShape) {
  SafeTensorsFile f;
  f.tensors["x"] = F32({3}, {1, 2});
  EXPECT_THROW(SerializeSafeTensors(f), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
