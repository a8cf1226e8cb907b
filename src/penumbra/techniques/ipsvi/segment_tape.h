#pragma once
// ipsvi's light segments as SIMD packets on the CPU. A viewing ray's samples
// each march a segment of their own light ray (light_segment.h), most of the
// frame's time; the samples come one at a time along the ray, so the ray is
// traced twice:
//  1. recording: the ray is traced with every segment's march recorded here
//     instead of run (the sample's light taken as 1, the cache not written);
//     which samples ask for light and how long their segments are depends
//     only on the samples' opacities, the cache's depths and the previous
//     sample's texel and depth, never on the light itself, so the recording
//     holds exactly the marches the real trace makes;
//  2. the recorded marches run 8 or 16 at a time (light_segment_depths_lanes
//     in ipsvi_packets.cpp);
//  3. replaying: the ray is traced again, each sample taking its segment's
//     optical depths from here, in the order they were recorded.
// A segment beyond the capacity is marched on its own during the replay.
// With the paper's light model (`emission`) the segments also carry the
// colour they add to the light (light_segment.h).
#include "penumbra/backends/cpu/packets.h"
#include "penumbra/techniques/ipsvi/light_segment.h"

#include <cstdint>

namespace penumbra {

struct SegmentTape {
  enum class Mode : std::uint8_t { Record, Replay };
  static constexpr int kCapacity = 512;  // a multiple of the widest packet
  static constexpr int kMaxWidth = 16;

  Mode mode = Mode::Record;
  int limit = kCapacity;  // segments recorded at most (tests lower it to exercise the overflow)
  bool emission = false;  // the paper's light model: emitted colour too
  int count = 0;        // segments recorded
  int next = 0;         // the next one to replay
  int checkpoints = 0;  // the most checkpoints of any recorded segment
  std::uint64_t samples = 0;  // samples the packets took
  float from[3][kCapacity];
  float to_light[3][kCapacity];
  float lengths[kMaxSegmentCheckpoints][kCapacity];  // 0 past a segment's own checkpoints
  float direct[kMaxSegmentCheckpoints][kCapacity];
  float diffuse[kMaxSegmentCheckpoints][3][kCapacity];
  float emitted[kMaxSegmentCheckpoints][3][kCapacity];

  void begin_recording(bool with_emission) {
    mode = Mode::Record;
    emission = with_emission;
    count = next = checkpoints = 0;
    samples = 0;
  }
  // Pads the recording to whole packets with segments of length 0 and
  // switches to replaying.
  void begin_replay() {
    for (int i = count; i < (count + kMaxWidth - 1) / kMaxWidth * kMaxWidth; ++i) {
      for (int a = 0; a < 3; ++a) from[a][i] = to_light[a][i] = 0.0f;
      to_light[2][i] = 1.0f;
      for (int j = 0; j < kMaxSegmentCheckpoints; ++j) lengths[j][i] = 0.0f;
    }
    mode = Mode::Replay;
    next = 0;
  }

  PENUMBRA_HD bool recording() const { return mode == Mode::Record; }

  // Records a segment (light_segment_depths' arguments); past the capacity
  // nothing, and the replay marches that segment itself.
  PENUMBRA_HD void record(vec3 p, vec3 toward_light, const float* segment_lengths, int n) {
    if (count >= limit) return;
    const int i = count++;
    for (int a = 0; a < 3; ++a) {
      from[a][i] = p[a];
      to_light[a][i] = toward_light[a];
    }
    for (int j = 0; j < kMaxSegmentCheckpoints; ++j) lengths[j][i] = j < n ? segment_lengths[j] : 0.0f;
    checkpoints = n > checkpoints ? n : checkpoints;
  }

  // The next recorded segment's optical depths; false past the recording.
  PENUMBRA_HD bool replay(OpticalDepth* depth, int n) {
    if (next >= count) return false;
    const int i = next++;
    for (int j = 0; j < n; ++j) {
      depth[j].direct = direct[j][i];
      depth[j].diffuse = vec3(diffuse[j][0][i], diffuse[j][1][i], diffuse[j][2][i]);
      depth[j].emitted = emission ? vec3(emitted[j][0][i], emitted[j][1][i], emitted[j][2][i]) : vec3(0.0f);
    }
    return true;
  }
};

// Marches the tape's recorded segments through view `shadow` as packets of
// Target and stores their optical depths in it. Defined only in the SIMD
// units of Target (ipsvi_packets.cpp).
template <SimdTarget Target>
void march_segment_tape(const RenderView& shadow, const ForwardScattering& scattering, SegmentTape& tape);
using SegmentTapeMarch = void (*)(const RenderView&, const ForwardScattering&, SegmentTape&);

}  // namespace penumbra
