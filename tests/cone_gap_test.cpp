// The best open gap of a sampled cone (collision::bestGap) against a cell-by-cell flood fill.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <optional>
#include <tuple>
#include <vector>

#include "collision/cone.h"
#include "plantarch/Random.h"

using namespace plantarch;

namespace {

// The gap as its definition reads (cone.h): open cells joined through shared edges (sectors
// wrap around, the innermost ring's cells all meet at the axis); each gap's directions summed
// cell by cell in cell order; the best score wins, ties going to the gap whose first run
// comes first (runs numbered ring by ring, each ring from its first blocked cell around).
std::optional<vec3> floodFillGap(const collision::ConeSample& s, float halfAngleDegrees) {
    const int rings = s.rings, sectors = s.sectors, n = rings * sectors;
    int hits = 0;
    for (int k = 0; k < n; ++k) hits += int(s.blocked[std::size_t(k)] != 0);
    if (hits == 0 || hits == n) return std::nullopt;
    auto open = [&](int i, int j) { return s.blocked[std::size_t(i * sectors + j)] == 0; };
    std::vector<int> gap(std::size_t(n), -1);
    int gaps = 0;
    for (int start = 0; start < n; ++start) {
        if (gap[std::size_t(start)] >= 0 || s.blocked[std::size_t(start)]) continue;
        std::deque<int> todo{start};
        gap[std::size_t(start)] = gaps;
        while (!todo.empty()) {
            const int k = todo.front();
            todo.pop_front();
            const int i = k / sectors, j = k % sectors;
            std::vector<std::pair<int, int>> next = {{i, (j + 1) % sectors},
                                                     {i, (j + sectors - 1) % sectors}};
            if (i > 0) next.push_back({i - 1, j});
            if (i + 1 < rings) next.push_back({i + 1, j});
            if (i == 0)
                for (int m = 0; m < sectors; ++m) next.push_back({0, m});
            for (auto [a, b] : next)
                if (open(a, b) && gap[std::size_t(a * sectors + b)] < 0) {
                    gap[std::size_t(a * sectors + b)] = gaps;
                    todo.push_back(a * sectors + b);
                }
        }
        ++gaps;
    }
    std::vector<int> size(std::size_t(gaps), 0);
    std::vector<vec3> sum(std::size_t(gaps), vec3(0.0f));
    std::vector<std::pair<int, int>> first(std::size_t(gaps), {rings, sectors});
    for (int i = 0; i < rings; ++i) {
        int blockedAt = -1;
        for (int j = 0; j < sectors && blockedAt < 0; ++j)
            if (!open(i, j)) blockedAt = j;
        for (int j = 0; j < sectors; ++j) {
            const int k = i * sectors + j, g = gap[std::size_t(k)];
            if (g < 0) continue;
            ++size[std::size_t(g)];
            sum[std::size_t(g)] += vec3(s.x[k], s.y[k], s.z[k]);
            const int place = blockedAt < 0 ? j : (j - blockedAt - 1 + sectors) % sectors;
            first[std::size_t(g)] = std::min(first[std::size_t(g)], {i, place});
        }
    }
    std::vector<int> order(static_cast<std::size_t>(gaps));
    for (int g = 0; g < gaps; ++g) order[std::size_t(g)] = g;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return first[std::size_t(a)] < first[std::size_t(b)]; });
    const float halfRad = halfAngleDegrees * 3.14159265358979f / 180.0f;
    float bestScore = -1.0f;
    vec3 best(0.0f);
    for (int g : order) {
        const float len = glm::length(sum[std::size_t(g)]);
        if (!(len > 1e-6f)) continue;
        const vec3 centre = sum[std::size_t(g)] / len;
        const float angle = std::acos(std::clamp(centre.z, -1.0f, 1.0f));
        const float score =
            float(size[std::size_t(g)]) / float(n) * (1.0f - 0.5f * angle / halfRad);
        if (score > bestScore) {
            bestScore = score;
            best = centre;
        }
    }
    if (bestScore < 0.0f) return std::nullopt;
    const vec3 w = best.x * s.e1 + best.y * s.e2 + best.z * s.axis;
    const float len = glm::length(w);
    return len > 1e-6f ? std::optional<vec3>(w / len) : std::nullopt;
}

bool sameBits(const std::optional<vec3>& a, const std::optional<vec3>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || std::memcmp(&*a, &*b, sizeof(vec3)) == 0;
}

}  // namespace

TEST(ConeGap, MatchesAFloodFillOfTheOpenCells) {
    Rng rng(5, 8);
    int compared = 0, found = 0;
    for (unsigned rays : {12u, 64u, 256u, 300u, 1000u, 1024u, 4096u, 5000u}) {
        for (float halfAngle : {30.0f, 80.0f, 150.0f}) {
            const auto patterns = collision::conePatterns(rays, halfAngle);
            for (int trial = 0; trial < 60; ++trial) {
                collision::ConeSample s;
                s.rings = patterns->rings;
                s.sectors = patterns->sectors;
                const int set = trial % collision::ConePatterns::kSets;
                s.x = patterns->x(set);
                s.y = patterns->y(set);
                s.z = patterns->z(set);
                s.e1 = glm::normalize(vec3(1.0f, 0.2f, 0.0f));
                s.axis = vec3(0.0f, 0.0f, 1.0f);
                s.e2 = glm::cross(s.axis, s.e1);
                const int n = s.rings * s.sectors;
                s.blocked.assign(std::size_t(n), 0u);
                if (trial % 3 == 0) {  // scattered cells
                    const float p = rng.uniform(0.05f, 0.95f);
                    for (auto& b : s.blocked) b = rng.uniform01() < p ? 1u : 0u;
                } else {  // blobs: patches of rings and sectors, some across sector 0
                    const int blobs = 1 + int(rng.nextU32() % 6);
                    for (int b = 0; b < blobs; ++b) {
                        const int i0 = int(rng.nextU32() % unsigned(s.rings));
                        const int j0 = int(rng.nextU32() % unsigned(s.sectors));
                        const int di = int(rng.nextU32() % unsigned(s.rings));
                        const int dj = int(rng.nextU32() % unsigned(s.sectors));
                        for (int i = i0; i <= std::min(s.rings - 1, i0 + di); ++i)
                            for (int j = j0; j <= j0 + dj; ++j)
                                s.blocked[std::size_t(i * s.sectors + j % s.sectors)] = 1u;
                    }
                    if (trial % 3 == 2)  // walls of single sectors through every ring
                        for (int i = 0; i < s.rings; ++i) {
                            s.blocked[std::size_t(i * s.sectors)] = 1u;
                            s.blocked[std::size_t(i * s.sectors + s.sectors / 2)] = 1u;
                        }
                }
                s.hits = 0;
                for (auto b : s.blocked) s.hits += int(b);
                const auto fast = collision::bestGap(s, halfAngle);
                const auto reference = floodFillGap(s, halfAngle);
                ASSERT_TRUE(sameBits(fast, reference))
                    << rays << " rays, half-angle " << halfAngle << ", trial " << trial;
                ++compared;
                found += fast.has_value();
            }
        }
    }
    std::printf("%d cones compared, %d with a gap\n", compared, found);
    EXPECT_GT(found, compared / 2);
}

TEST(ConeGap, NothingWhenAllOpenOrAllBlocked) {
    const auto patterns = collision::conePatterns(256, 80.0f);
    collision::ConeSample s;
    s.rings = patterns->rings;
    s.sectors = patterns->sectors;
    s.x = patterns->x(0);
    s.y = patterns->y(0);
    s.z = patterns->z(0);
    s.blocked.assign(std::size_t(s.rings * s.sectors), 0u);
    s.hits = 0;
    EXPECT_FALSE(collision::bestGap(s, 80.0f));
    std::fill(s.blocked.begin(), s.blocked.end(), 1u);
    s.hits = s.rings * s.sectors;
    EXPECT_FALSE(collision::bestGap(s, 80.0f));
    // One open cell in the outermost ring: the gap is its direction.
    s.blocked[std::size_t(s.rings * s.sectors - 3)] = 0u;
    --s.hits;
    const auto gap = collision::bestGap(s, 80.0f);
    ASSERT_TRUE(gap);
    const int k = s.rings * s.sectors - 3;
    const vec3 d = glm::normalize(s.x[k] * s.e1 + s.y[k] * s.e2 + s.z[k] * s.axis);
    EXPECT_NEAR(glm::dot(*gap, d), 1.0f, 1e-6f);
}
