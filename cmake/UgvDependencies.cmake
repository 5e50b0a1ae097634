# Every dependency is a Debian 12 package; tools/install-deps installs them.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm)
pkg_check_modules(SYSTEMD REQUIRED IMPORTED_TARGET libsystemd)
pkg_check_modules(GEOGRAPHICLIB REQUIRED IMPORTED_TARGET geographiclib)
# lib/foxglove's MCAP writer: chunk compression and CRC-32.
pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET liblz4)
pkg_check_modules(ZLIB REQUIRED IMPORTED_TARGET zlib)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(spdlog REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(Catch2 2 REQUIRED)
find_package(Threads REQUIRED)
find_package(benchmark QUIET)
find_package(Java COMPONENTS Development QUIET)
find_path(CLI11_INCLUDE_DIR CLI/CLI.hpp REQUIRED)
find_program(LCM_GEN lcm-gen REQUIRED)
find_file(LCM_JAR lcm.jar PATHS /usr/share/java NO_DEFAULT_PATH)
# ugv-foxglove: websocketpp on standalone asio, nlohmann-json (header-only Debian packages:
# libwebsocketpp-dev libasio-dev nlohmann-json3-dev, from tools/install-deps).
find_path(WEBSOCKETPP_INCLUDE_DIR websocketpp/server.hpp REQUIRED)
find_path(ASIO_INCLUDE_DIR asio.hpp REQUIRED)
find_path(NLOHMANN_JSON_INCLUDE_DIR nlohmann/json.hpp REQUIRED)
