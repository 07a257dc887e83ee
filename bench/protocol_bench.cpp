// XDR encode/decode of the frames a session exchanges every cycle (the client's CONTROL_OBJECT,
// the controller's ANSWER), against copying the same decoded struct: the price of a portable,
// checked (CRC, ranges) wire format over handing memory across.
#include <benchmark/benchmark.h>

#include <array>
#include <cstring>

#include "hapticctrl/protocol/codec.hpp"
#include "support/ratio_reporter.hpp"

namespace {

namespace proto = hapticctrl::protocol;

hcp_frame object_frame() {
  hcp_frame f = proto::make_frame(HCP_CONTROL_OBJECT, 0x1234'5678'9abc'def0ULL, 42, 1'000'000);
  auto& o = f.body.hcp_body_u.object;
  const std::array<float, 7> pose{0.63F, 0.01F, 0.23F, 0.0F, 0.0F, 0.0F, 1.0F};
  std::memcpy(o.pose, pose.data(), sizeof o.pose);
  return f;
}

hcp_frame answer_frame() {
  hcp_frame f = proto::make_frame(HCP_ANSWER, 0x1234'5678'9abc'def0ULL, 43, 2'000'000);
  auto& a = f.body.hcp_body_u.answer;
  a.cycle = 123456;
  a.state_word = 1;
  a.core_state = 1;
  a.handle_pose[6] = 1.0;
  return f;
}

template <hcp_frame (*Make)()>
void BM_Encode(benchmark::State& state) {
  hcp_frame f = Make();
  std::array<std::uint8_t, 512> buffer{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(proto::encode(f, buffer));
    benchmark::ClobberMemory();
  }
}

template <hcp_frame (*Make)()>
void BM_Decode(benchmark::State& state) {
  hcp_frame f = Make();
  std::array<std::uint8_t, 512> buffer{};
  const std::size_t n = proto::encode(f, buffer);
  hcp_frame out{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(proto::decode({buffer.data(), n}, out));
    benchmark::ClobberMemory();
  }
}

/// The baseline: the same decoded frame copied as memory.
void BM_CopyFrameStruct(benchmark::State& state) {
  const hcp_frame f = answer_frame();
  hcp_frame out{};
  for (auto _ : state) {
    std::memcpy(&out, &f, sizeof f);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
}

BENCHMARK(BM_CopyFrameStruct);
BENCHMARK(BM_Encode<object_frame>)->Name("BM_EncodeControlObject");
BENCHMARK(BM_Decode<object_frame>)->Name("BM_DecodeControlObject");
BENCHMARK(BM_Encode<answer_frame>)->Name("BM_EncodeAnswer");
BENCHMARK(BM_Decode<answer_frame>)->Name("BM_DecodeAnswer");

}  // namespace

int main(int argc, char** argv) {
  return hapticctrl::bench::run_with_ratios(argc, argv,
                                            {{"BM_EncodeAnswer", "BM_CopyFrameStruct"},
                                             {"BM_DecodeAnswer", "BM_CopyFrameStruct"},
                                             {"BM_EncodeControlObject", "BM_CopyFrameStruct"},
                                             {"BM_DecodeControlObject", "BM_CopyFrameStruct"}},
                                            [](const hapticctrl::bench::RatioReporter&) {});
}
