// Times the rotation of two versions of lib/terrain side by side (see rotation.sh): the
// calls alternate, A then B, then B then A, so that the host's speed, which moves by tens
// of per cent from one minute to the next on a shared machine, is the same for both, and
// the median of the per-pair ratios is the figure.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace ugvA::side_by_side {
void make_map(int n, double known_radius_m);
double time_rotation();
double checksum();
}  // namespace ugvA::side_by_side
namespace ugvB::side_by_side {
void make_map(int n, double known_radius_m);
double time_rotation();
double checksum();
}  // namespace ugvB::side_by_side

namespace {
double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}
}  // namespace

int main(int argc, char** argv)
{
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s CELLS_A_SIDE KNOWN_RADIUS_M PAIRS\n", argv[0]);
        return 2;
    }
    const int n = std::atoi(argv[1]);
    const double known_radius_m = std::atof(argv[2]);
    const int pairs = std::atoi(argv[3]);
    if (n < 8 || pairs < 1) {
        std::fprintf(stderr, "rotation_side_by_side: need at least 8 cells a side and 1 pair\n");
        return 2;
    }
    ugvA::side_by_side::make_map(n, known_radius_m);
    ugvB::side_by_side::make_map(n, known_radius_m);
    std::vector<double> a, b, ratio;
    for (int k = 0; k < pairs; ++k) {
        double ta = 0.0, tb = 0.0;
        if (k % 2 == 0) {
            ta = ugvA::side_by_side::time_rotation();
            tb = ugvB::side_by_side::time_rotation();
        } else {
            tb = ugvB::side_by_side::time_rotation();
            ta = ugvA::side_by_side::time_rotation();
        }
        a.push_back(ta);
        b.push_back(tb);
        ratio.push_back(tb / ta);
    }
    const double sum_a = ugvA::side_by_side::checksum(), sum_b = ugvB::side_by_side::checksum();
    std::printf("%dx%d map%s, %d pairs (us): A min %.1f median %.1f | B min %.1f median %.1f | "
                "B/A median %.3f (quartiles %.3f-%.3f) | checksum A %.9g B %.9g\n",
                n, n, known_radius_m > 0.0 ? " partly known" : "", pairs, quantile(a, 0.0), quantile(a, 0.5),
                quantile(b, 0.0), quantile(b, 0.5), quantile(ratio, 0.5), quantile(ratio, 0.25),
                quantile(ratio, 0.75), sum_a, sum_b);
    return 0;
}
