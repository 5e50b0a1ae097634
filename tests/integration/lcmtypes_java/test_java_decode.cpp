// C++ encodes one message of every type into a log; the generated Java classes (the jar that
// lcm-spy loads) decode each, found by fingerprint, with the same values.
#include <catch2/catch.hpp>

#include <sstream>

#include "ugv_test/process.hpp"
#include "ugv_test/sample_messages.hpp"

TEST_CASE("the Java classes in ugv_lcmtypes.jar decode every C++-encoded ugv message")
{
    ugv::test::TempDir dir;
    std::vector<std::string> names;
    {
        auto w = ugv::bus::open_log_writer(dir / "all.lcm", [] { return int64_t{1}; });
        names = ugv::test::publish_samples(*w);
    }
    REQUIRE(names.size() == 14);
    const int code = ugv::test::run({JAVA_EXECUTABLE, "-cp", JAVA_CLASSPATH, "DecodeAll", dir / "all.lcm", UGV_TYPES_JAR},
                                    dir / "out", dir / "err", 120);
    INFO(ugv::test::read_file(dir / "err"));
    REQUIRE(code == 0);
    std::istringstream out(ugv::test::read_file(dir / "out"));
    std::vector<std::string> lines;
    for (std::string l; std::getline(out, l);) lines.push_back(l);
    REQUIRE(lines.size() == 14);
    for (std::size_t k = 0; k < 14; ++k) {
        INFO(lines[k]);
        CHECK(lines[k].rfind("SAMPLE_" + names[k] + "\tugv." + names[k] + "\t", 0) == 0);
        CHECK(lines[k].find("\tutime=" + std::to_string(1000 + k) + "\tseq=" + std::to_string(10 + k)) != std::string::npos);
    }
    CHECK(lines[0].find("\tsensor_id=front\t") != std::string::npos);
    CHECK(lines[0].find("\tranges=[1.25, NaN]\tflags=[0, 2]") != std::string::npos);
    CHECK(lines[3].find("\tlatitude=50.25\tlongitude=-110.5") != std::string::npos);
    CHECK(lines[8].find("\tcount=[3, 0]") != std::string::npos);
    CHECK(lines[9].find("\tcounter_names=[scans]\tcounter_values=[375]") != std::string::npos);
    CHECK(lines[10].find("\tdata=[2, -128, -1]") != std::string::npos);
    CHECK(lines[12].find("\tcell_class=[2, 0]\tcost=[1.0, NaN]") != std::string::npos);
    CHECK(lines[13].find("\tblocked=[1, 0]\tbest=1") != std::string::npos);
}
