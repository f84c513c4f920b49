// Welding by exact position (geometry/position_welding.h): each position's
// 64-bit hash picks one of kPartitions partitions (its top bits) and a slot
// in that partition's open-addressing table (linear probing, at most half
// full, the partition's own distinct positions beside it), so that the
// partitions weld in parallel with small tables. The distinct positions are
// then numbered in the order of the first vertex holding each, as a serial
// welder would: nearby vertices keep nearby numbers, which the normals'
// per-vertex arrays rely on for their locality.
#include "geometry/position_welding.h"

#include <array>
#include <bit>
#include <limits>
#include <stdexcept>
#include <utility>

#include "geometry/parallel_indices.h"

namespace quiver {

namespace {

constexpr unsigned kPartitionBits = 6;
constexpr std::size_t kPartitions = std::size_t{1} << kPartitionBits;
constexpr std::uint32_t kEmpty = std::numeric_limits<std::uint32_t>::max();

using Key = std::array<std::uint32_t, 3>;

Key key_of(const Vec3<float>& q) {
  return {std::bit_cast<std::uint32_t>(q.x), std::bit_cast<std::uint32_t>(q.y), std::bit_cast<std::uint32_t>(q.z)};
}

// A 64-bit mix of the three words (multiply and xor-shift: every bit reaches
// the top bits, which pick the partition, and the slot bits).
std::uint64_t mix(const Key& k) {
  std::uint64_t h = (std::uint64_t{k[0]} << 32 | k[1]) * 0x9E3779B97F4A7C15ull;
  h ^= (h >> 29) + std::uint64_t{k[2]} * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 32;
  return h * 0x94D049BB133111EBull;
}

std::size_t partition_of(std::uint64_t hash) { return static_cast<std::size_t>(hash >> (64 - kPartitionBits)); }

// One partition's vertices (in input order) welded: local[k] is the number
// of vertices[k]'s position among the partition's distinct ones, numbered
// in the order first met; first_vertex[j] the vertex that met j first.
struct Partition {
  std::vector<std::uint32_t> vertices, local, first_vertex;
  std::vector<Vec3<float>> distinct;

  void weld(const std::vector<Vec3<float>>& positions) {
    std::vector<std::uint32_t> slots(std::bit_ceil(std::max<std::size_t>(2 * vertices.size(), 16)), kEmpty);
    const std::size_t mask = slots.size() - 1;
    local.resize(vertices.size());
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      const Vec3<float>& q = positions[vertices[k]];
      const Key key = key_of(q);
      std::size_t slot = static_cast<std::size_t>(mix(key) >> 16) & mask;
      while (slots[slot] != kEmpty && key_of(distinct[slots[slot]]) != key) slot = (slot + 1) & mask;
      if (slots[slot] == kEmpty) {
        slots[slot] = static_cast<std::uint32_t>(distinct.size());
        distinct.push_back(q);
        first_vertex.push_back(vertices[k]);
      }
      local[k] = slots[slot];
    }
  }
};

}  // namespace

WeldedPositions weld_positions(std::size_t count, const std::function<Vec3<float>(std::size_t)>& position_at) {
  if (count >= std::size_t{kEmpty}) throw std::length_error("weld_positions: 2^32 - 1 positions at most");
  // Each position with -0 made +0 (the sum), and its partition.
  std::vector<Vec3<float>> positions(count);
  std::vector<std::uint8_t> partition(count);
  for_each_index(count, [&](std::size_t i) {
    const Vec3<float> p = position_at(i);
    positions[i] = {p.x + 0.f, p.y + 0.f, p.z + 0.f};
    partition[i] = static_cast<std::uint8_t>(partition_of(mix(key_of(positions[i]))));
  });
  std::array<Partition, kPartitions> parts;
  {
    std::array<std::size_t, kPartitions> sizes{};
    for (std::uint8_t p : partition) ++sizes[p];
    for (std::size_t p = 0; p < kPartitions; ++p) parts[p].vertices.reserve(sizes[p]);
  }
  for (std::size_t i = 0; i < count; ++i) parts[partition[i]].vertices.push_back(static_cast<std::uint32_t>(i));
  for_each_task(kPartitions, [&](std::size_t p) { parts[p].weld(positions); });

  // The first vertices in input order are the distinct positions' numbers.
  WeldedPositions welded;
  welded.index_of.assign(count, kEmpty);
  for_each_task(kPartitions, [&](std::size_t p) {
    for (std::uint32_t v : parts[p].first_vertex) welded.index_of[v] = 0;
  });
  std::uint32_t distinct = 0;
  for (std::uint32_t& number : welded.index_of) {
    if (number == 0) number = distinct++;
  }
  welded.positions.resize(distinct);
  for_each_task(kPartitions, [&](std::size_t p) {
    const Partition& part = parts[p];
    for (std::size_t j = 0; j < part.first_vertex.size(); ++j) {
      welded.positions[welded.index_of[part.first_vertex[j]]] = part.distinct[j];
    }
    for (std::size_t k = 0; k < part.vertices.size(); ++k) {
      welded.index_of[part.vertices[k]] = welded.index_of[part.first_vertex[part.local[k]]];
    }
  });
  return welded;
}

void number_by_first_use(std::vector<Vec3<float>>& positions, std::span<std::array<std::uint32_t, 3>> triangles) {
  std::vector<std::uint32_t> number(positions.size(), kEmpty);
  std::vector<Vec3<float>> used;
  for (std::array<std::uint32_t, 3>& t : triangles) {
    for (std::uint32_t& v : t) {
      if (number[v] == kEmpty) {
        number[v] = static_cast<std::uint32_t>(used.size());
        used.push_back(positions[v]);
      }
      v = number[v];
    }
  }
  positions = std::move(used);
}

}  // namespace quiver
