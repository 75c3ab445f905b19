// PackedAnswerWriter: protobuf's wire format of GetPointsResponse, written by
// hand for its packed case (each field a tag, a varint length, the bytes).
#include "server/packed_answer.h"

#include <array>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "scallop/geometry/double_lanes.h"
#include "scallop/plane/plane_engine.h"

namespace scallop::server {
namespace {

// Tags (field number << 3 | wire type 2, length-delimited) of the fields written.
constexpr char kResponsePoints = 0x0A;  // GetPointsResponse.points = 1
constexpr char kResponseToken = 0x12;   // GetPointsResponse.next_page_token = 2
constexpr char kResponseWorld = 0x1A;   // GetPointsResponse.world = 3
constexpr char kPointsXs = 0x0A;        // Points.xs = 1
constexpr char kPointsYs = 0x12;        // Points.ys = 2
constexpr char kPointsIds = 0x1A;       // Points.ids = 3

// Two points' x and y, swapped across two SSE2-wide vectors (plain code where
// there is none).
struct PointPair {
  Doubles x;
  Doubles y;
};
PointPair LoadPair(const Vec2* points) {
  Doubles first, second;
  std::memcpy(&first, &points[0], sizeof first);
  std::memcpy(&second, &points[1], sizeof second);
  return {__builtin_shufflevector(first, second, 0, 2),
          __builtin_shufflevector(first, second, 1, 3)};
}

// The points [k, count) of AppendInsideOf's points, one at a time, after
// `kept` kept; returns how many are kept in all.
template <int kSides>
size_t AppendInsideOneByOne(const Vec2* points, size_t k, size_t count, uint64_t first_id,
                            const Rect& rect, double* __restrict xs, double* __restrict ys,
                            uint64_t* __restrict ids, size_t kept) {
  for (; k < count; ++k) {
    xs[kept] = points[k].x;
    ys[kept] = points[k].y;
    ids[kept] = first_id + k;
    kept += InsideOnSides<kSides>(rect, points[k]);
  }
  return kept;
}

// AppendInside for the sides kSides of `rect` (CuttingSides' bits). Two points
// at a time, each side one comparison of both, whose lanes are -1 (inside) or
// 0; each point is then stored at `kept`, and `kept` moves past it by its
// lane's truth, negated.
template <int kSides>
size_t AppendInsideOf(const Vec2* points, size_t count, uint64_t first_id, const Rect& rect,
                      double* __restrict xs, double* __restrict ys, uint64_t* __restrict ids) {
  const Doubles x0 = {rect.x0, rect.x0};
  const Doubles x1 = {rect.x1, rect.x1};
  const Doubles y0 = {rect.y0, rect.y0};
  const Doubles y1 = {rect.y1, rect.y1};
  size_t kept = 0;
  size_t k = 0;
  for (; k + 2 <= count; k += 2) {
    const PointPair pair = LoadPair(points + k);
    DoubleBits inside = {-1, -1};
    if constexpr ((kSides & 1) != 0) inside &= x0 <= pair.x;
    if constexpr ((kSides & 2) != 0) inside &= pair.x < x1;
    if constexpr ((kSides & 4) != 0) inside &= y0 <= pair.y;
    if constexpr ((kSides & 8) != 0) inside &= pair.y < y1;
    xs[kept] = pair.x[0];
    ys[kept] = pair.y[0];
    ids[kept] = first_id + k;
    kept -= static_cast<size_t>(inside[0]);
    xs[kept] = pair.x[1];
    ys[kept] = pair.y[1];
    ids[kept] = first_id + k + 1;
    kept -= static_cast<size_t>(inside[1]);
  }
  return AppendInsideOneByOne<kSides>(points, k, count, first_id, rect, xs, ys, ids, kept);
}

#if defined(__x86_64__)
// The four-lane loops: AVX2 for four points at a time, compiled for it here
// and called only where the CPU has it (CpuHasAvx2).
#define SCALLOP_AVX2 __attribute__((target("avx2,popcnt")))

bool CpuHasAvx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt"); }

// The x and y of points[0, 4), each in its lanes in order.
struct FourPoints {
  __m256d x;
  __m256d y;
};
SCALLOP_AVX2 inline FourPoints LoadFour(const Vec2* points) {
  const __m256d first = _mm256_loadu_pd(&points[0].x);   // x0 y0 x1 y1
  const __m256d second = _mm256_loadu_pd(&points[2].x);  // x2 y2 x3 y3
  // unpacklo: x0 x2 x1 x3; lanes 0, 2, 1, 3 of it in order.
  return {_mm256_permute4x64_pd(_mm256_unpacklo_pd(first, second), 0xD8),
          _mm256_permute4x64_pd(_mm256_unpackhi_pd(first, second), 0xD8)};
}

// For each 4-bit mask of lanes kept, the 32-bit lanes that move the kept
// 64-bit lanes to the front, in order (the rest are left as lane 0).
struct CompressTable {
  alignas(32) int32_t lanes[16][8];
};
constexpr CompressTable MakeCompressTable() {
  CompressTable table{};
  for (int mask = 0; mask < 16; ++mask) {
    int out = 0;
    for (int lane = 0; lane < 4; ++lane) {
      if ((mask >> lane & 1) == 0) continue;
      table.lanes[mask][2 * out] = 2 * lane;
      table.lanes[mask][2 * out + 1] = 2 * lane + 1;
      ++out;
    }
  }
  return table;
}
constexpr CompressTable kCompress = MakeCompressTable();

SCALLOP_AVX2 void AppendRunInFourLanes(const Vec2* points, size_t count, uint64_t first_id,
                                       double* __restrict xs, double* __restrict ys,
                                       uint64_t* __restrict ids) {
  __m256i id = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<int64_t>(first_id)),
                                _mm256_setr_epi64x(0, 1, 2, 3));
  const __m256i four = _mm256_set1_epi64x(4);
  size_t k = 0;
  for (; k + 4 <= count; k += 4) {
    const FourPoints four_points = LoadFour(points + k);
    _mm256_storeu_pd(xs + k, four_points.x);
    _mm256_storeu_pd(ys + k, four_points.y);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(ids + k), id);
    id = _mm256_add_epi64(id, four);
  }
  for (; k < count; ++k) {
    xs[k] = points[k].x;
    ys[k] = points[k].y;
    ids[k] = first_id + k;
  }
}

// AppendInsideOf in four lanes: each side one comparison of four points, the
// kept lanes moved to the front (kCompress) and all four stored at `kept`,
// which moves past the kept ones. The stores of points [k, k + 4) end before
// index k + 4 <= count: within the room for all `count` that AppendInside
// requires, as the two-lane loop's.
template <int kSides>
SCALLOP_AVX2 size_t AppendInsideInFourLanes(const Vec2* points, size_t count, uint64_t first_id,
                                            const Rect& rect, double* __restrict xs,
                                            double* __restrict ys, uint64_t* __restrict ids) {
  const __m256d x0 = _mm256_set1_pd(rect.x0);
  const __m256d x1 = _mm256_set1_pd(rect.x1);
  const __m256d y0 = _mm256_set1_pd(rect.y0);
  const __m256d y1 = _mm256_set1_pd(rect.y1);
  __m256i id = _mm256_add_epi64(_mm256_set1_epi64x(static_cast<int64_t>(first_id)),
                                _mm256_setr_epi64x(0, 1, 2, 3));
  const __m256i four = _mm256_set1_epi64x(4);
  size_t kept = 0;
  size_t k = 0;
  for (; k + 4 <= count; k += 4) {
    const FourPoints p = LoadFour(points + k);
    // As InsideOnSides: ordered comparisons, false for a NaN.
    __m256d inside = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
    if constexpr ((kSides & 1) != 0) {
      inside = _mm256_and_pd(inside, _mm256_cmp_pd(x0, p.x, _CMP_LE_OQ));
    }
    if constexpr ((kSides & 2) != 0) {
      inside = _mm256_and_pd(inside, _mm256_cmp_pd(p.x, x1, _CMP_LT_OQ));
    }
    if constexpr ((kSides & 4) != 0) {
      inside = _mm256_and_pd(inside, _mm256_cmp_pd(y0, p.y, _CMP_LE_OQ));
    }
    if constexpr ((kSides & 8) != 0) {
      inside = _mm256_and_pd(inside, _mm256_cmp_pd(p.y, y1, _CMP_LT_OQ));
    }
    const int mask = _mm256_movemask_pd(inside);
    const __m256i move = _mm256_load_si256(reinterpret_cast<const __m256i*>(kCompress.lanes[mask]));
    _mm256_storeu_pd(xs + kept,
                     _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(p.x), move)));
    _mm256_storeu_pd(ys + kept,
                     _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(p.y), move)));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(ids + kept),
                        _mm256_permutevar8x32_epi32(id, move));
    kept += static_cast<size_t>(_mm_popcnt_u32(static_cast<unsigned>(mask)));
    id = _mm256_add_epi64(id, four);
  }
  return AppendInsideOneByOne<kSides>(points, k, count, first_id, rect, xs, ys, ids, kept);
}
#undef SCALLOP_AVX2
#else
bool CpuHasAvx2() { return false; }
#endif

size_t VarintSize(uint64_t value) {
  size_t size = 1;
  for (; value >= 0x80; value >>= 7) ++size;
  return size;
}

void AppendHeader(std::string& out, char tag, uint64_t length) {
  out.push_back(tag);
  for (; length >= 0x80; length >>= 7) out.push_back(static_cast<char>((length & 0x7F) | 0x80));
  out.push_back(static_cast<char>(length));
}

}  // namespace

PackedAnswerWriter::PackedAnswerWriter(size_t capacity, CopyLanes lanes)
    : capacity_(capacity),
      data_(3 * sizeof(double) * capacity),
      four_lanes_(lanes == CopyLanes::kFastest && CpuHasAvx2()) {
  // The slice is ours alone until Finish shares it; grpc::Slice hands out only const bytes.
  auto* bytes = const_cast<uint8_t*>(data_.begin());
  xs_ = reinterpret_cast<double*>(bytes);
  ys_ = reinterpret_cast<double*>(bytes + sizeof(double) * capacity_);
  ids_ = reinterpret_cast<uint64_t*>(bytes + 2 * sizeof(double) * capacity_);
}

void PackedAnswerWriter::AppendRun(const Vec2* points, size_t count, uint64_t first_id) {
#if defined(__x86_64__)
  if (four_lanes_) {
    AppendRunInFourLanes(points, count, first_id, xs_ + count_, ys_ + count_, ids_ + count_);
    count_ += static_cast<uint32_t>(count);
    return;
  }
#endif
  // Two points at a time (LoadPair): half the instructions of a point at a
  // time, most of a warm tile being whole regions.
  double* __restrict xs = xs_ + count_;
  double* __restrict ys = ys_ + count_;
  uint64_t* __restrict ids = ids_ + count_;
  size_t k = 0;
  for (; k + 2 <= count; k += 2) {
    const PointPair pair = LoadPair(points + k);
    std::memcpy(xs + k, &pair.x, sizeof pair.x);
    std::memcpy(ys + k, &pair.y, sizeof pair.y);
    ids[k] = first_id + k;
    ids[k + 1] = first_id + k + 1;
  }
  for (; k < count; ++k) {
    xs[k] = points[k].x;
    ys[k] = points[k].y;
    ids[k] = first_id + k;
  }
  count_ += static_cast<uint32_t>(count);
}

size_t PackedAnswerWriter::AppendInside(const Vec2* points, size_t count, uint64_t first_id,
                                        const Rect& rect, int sides) {
  const size_t kept = WithCuttingSides(sides, [&](auto cutting) {
#if defined(__x86_64__)
    if (four_lanes_) {
      return AppendInsideInFourLanes<decltype(cutting)::value>(
          points, count, first_id, rect, xs_ + count_, ys_ + count_, ids_ + count_);
    }
#endif
    return AppendInsideOf<decltype(cutting)::value>(points, count, first_id, rect, xs_ + count_,
                                                    ys_ + count_, ids_ + count_);
  });
  count_ += static_cast<uint32_t>(kept);
  return kept;
}

grpc::ByteBuffer PackedAnswerWriter::Finish(std::string_view next_page_token,
                                            std::string_view world_message) const {
  const uint64_t array_bytes = sizeof(double) * uint64_t{count_};
  // Empty packed fields are not written; the points message is, even empty.
  const uint64_t points_bytes = count_ == 0 ? 0 : 3 * (1 + VarintSize(array_bytes) + array_bytes);
  std::array<grpc::Slice, 7> slices;
  size_t used = 0;
  std::string head;
  AppendHeader(head, kResponsePoints, points_bytes);
  if (count_ > 0) {
    const size_t field = sizeof(double) * capacity_;  // each array's room in data_
    AppendHeader(head, kPointsXs, array_bytes);
    slices[used++] = grpc::Slice(head);
    slices[used++] = data_.sub(0, array_bytes);
    std::string header;
    AppendHeader(header, kPointsYs, array_bytes);
    slices[used++] = grpc::Slice(header);
    slices[used++] = data_.sub(field, field + array_bytes);
    header.clear();
    AppendHeader(header, kPointsIds, array_bytes);
    slices[used++] = grpc::Slice(header);
    slices[used++] = data_.sub(2 * field, 2 * field + array_bytes);
    head.clear();
  }
  std::string& tail = head;
  if (!next_page_token.empty()) {
    AppendHeader(tail, kResponseToken, next_page_token.size());
    tail += next_page_token;
  }
  AppendHeader(tail, kResponseWorld, world_message.size());
  tail += world_message;
  slices[used++] = grpc::Slice(tail);
  return grpc::ByteBuffer(slices.data(), used);
}

}  // namespace scallop::server
