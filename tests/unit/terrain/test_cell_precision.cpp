// The cell keeps its sums in float (32 bytes a cell). These tests show that eq. 23 and 32
// stay as accurate as a double computation where the terrain map works: ENU heights of
// hundreds of metres with millimetre noise. The reference is computed in double with the
// two-pass form of eq. 25, sum w (z - mean)^2 / sum w, which has no cancellation.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "ugv/terrain/cell_sums.hpp"

using namespace ugv::terrain;

namespace {

struct Sample
{
    double z_m;
    float w;
};

struct Reference
{
    double mean_m, variance_m2;
};

Reference two_pass(const std::vector<Sample>& samples)
{
    double w = 0.0, wz = 0.0;
    for (const Sample& s : samples) {
        w += s.w;
        wz += s.w * s.z_m;
    }
    const double mean = wz / w;
    double spread = 0.0;
    for (const Sample& s : samples) spread += s.w * (s.z_m - mean) * (s.z_m - mean);
    return {mean, spread / w};
}

// Heights around z0 with Gaussian noise sigma, weights 1/s^2 for s between 1 mm and 3 cm
// (the sensor part and eq. 19 at 2 to 16 m).
std::vector<Sample> noisy_samples(double z0_m, double sigma_m, int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma_m);
    std::uniform_real_distribution<double> s_m(0.001, 0.03);
    std::vector<Sample> out;
    for (int k = 0; k < count; ++k) {
        const double s = s_m(rng);
        out.push_back({z0_m + noise(rng), static_cast<float>(1.0 / (s * s))});
    }
    return out;
}

}  // namespace

TEST_CASE("eq. 23 and 32 in float about the cell's reference match double at 750 m with mm noise")
{
    for (int count : {2, 10, 1000, 100000}) {
        const std::vector<Sample> samples = noisy_samples(750.0, 0.001, count, 7u + static_cast<unsigned>(count));
        CellSums c;
        for (const Sample& s : samples) fuse_sample(c, 0.0f, 0.0f, s.z_m, s.w);
        const Reference ref = two_pass(samples);
        const CellStatistics got = cell_statistics(c, StatisticsKind::variance_weighted);
        INFO("samples " << count << ": variance " << got.variance_z_m2 << " vs " << ref.variance_m2);
        CHECK(std::abs(got.mean_z_m - ref.mean_m) < 1e-6);  // 1 um
        CHECK(got.variance_z_m2 == Approx(ref.variance_m2).epsilon(1e-3));
    }
}

TEST_CASE("the reference height is what makes float enough: sums of ENU heights would not be")
{
    // The same samples as above fused as absolute heights into float sums: eq. 32 then
    // subtracts two numbers of ~(750 m)^2 W that agree to 12 digits, beyond float's 7.
    const std::vector<Sample> samples = noisy_samples(750.0, 0.001, 1000, 1007u);
    float w = 0.0f, wz = 0.0f, wz2 = 0.0f;
    for (const Sample& s : samples) {
        const float z = static_cast<float>(s.z_m);
        w += s.w;
        wz += s.w * z;
        wz2 += s.w * z * z;
    }
    const double naive = (static_cast<double>(w) * wz2 - static_cast<double>(wz) * wz) / (static_cast<double>(w) * w);
    const Reference ref = two_pass(samples);
    CHECK(std::abs(naive - ref.variance_m2) > 100.0 * ref.variance_m2);
}

TEST_CASE("classical statistics (eq. 21-22) in float match double at 750 m")
{
    std::vector<Sample> samples = noisy_samples(750.0, 0.002, 5000, 11u);
    CellSums c;
    double sum = 0.0, sum2 = 0.0;
    for (const Sample& s : samples) {
        fuse_sample(c, 0.0f, 0.0f, s.z_m, 1.0f);
        sum += s.z_m;
    }
    const double mean = sum / static_cast<double>(samples.size());
    for (const Sample& s : samples) sum2 += (s.z_m - mean) * (s.z_m - mean);
    const CellStatistics got = cell_statistics(c, StatisticsKind::classical);
    CHECK(std::abs(got.mean_z_m - mean) < 1e-6);
    CHECK(got.variance_z_m2 == Approx(sum2 / static_cast<double>(samples.size() - 1)).epsilon(1e-3));
}

TEST_CASE("merging cells of different references and recentring keep eq. 32 exact")
{
    // Two halves of a cell, one 0.3 m higher (an obstacle edge), fused separately and merged
    // as the rotation does; then recentred on the mean and fused on.
    const std::vector<Sample> low = noisy_samples(750.0, 0.001, 3000, 21u);
    const std::vector<Sample> high = noisy_samples(750.3, 0.001, 3000, 22u);
    CellSums a, b;
    for (const Sample& s : low) fuse_sample(a, 0.0f, 0.0f, s.z_m, s.w);
    for (const Sample& s : high) fuse_sample(b, 0.0f, 0.0f, s.z_m, s.w);
    add_sums(a, b);
    std::vector<Sample> all = low;
    all.insert(all.end(), high.begin(), high.end());
    Reference ref = two_pass(all);
    CHECK(cell_statistics(a, StatisticsKind::variance_weighted).variance_z_m2 == Approx(ref.variance_m2).epsilon(1e-4));
    recentre(a);
    CHECK(std::abs(a.z_ref_m - ref.mean_m) < 3.1e-5);  // the float nearest the mean (steps of 6.1e-5 at 750 m)
    CHECK(std::abs(a.z_wz) < 1e-3 * a.w * 0.15);  // ~0 about the mean
    CHECK(cell_statistics(a, StatisticsKind::variance_weighted).mean_z_m == Approx(ref.mean_m).epsilon(1e-9));
    const std::vector<Sample> more = noisy_samples(750.15, 0.001, 3000, 23u);
    for (const Sample& s : more) fuse_sample(a, 0.0f, 0.0f, s.z_m, s.w);
    all.insert(all.end(), more.begin(), more.end());
    ref = two_pass(all);
    CHECK(cell_statistics(a, StatisticsKind::variance_weighted).variance_z_m2 == Approx(ref.variance_m2).epsilon(1e-4));
}

TEST_CASE("a light first sample far from the rest does not stay the reference")
{
    // The float sums' rounding is relative to sum w (z - ref)^2: with the 0.5 m outlier as
    // the reference for good, 20000 samples would put the variance 10 % off. The first
    // heavier sample takes over as the reference.
    std::vector<Sample> samples = {{750.5, 1.0f}};
    const std::vector<Sample> rest = noisy_samples(750.0, 0.001, 20000, 31u);
    samples.insert(samples.end(), rest.begin(), rest.end());
    CellSums c;
    for (const Sample& s : samples) fuse_sample(c, 0.0f, 0.0f, s.z_m, s.w);
    const Reference ref = two_pass(samples);
    const CellStatistics got = cell_statistics(c, StatisticsKind::variance_weighted);
    CHECK(std::abs(c.z_ref_m - 750.0f) < 0.01f);
    CHECK(got.variance_z_m2 == Approx(ref.variance_m2).epsilon(1e-3));
    CHECK(std::abs(got.mean_z_m - ref.mean_m) < 1e-6);
}
