// The one Catch2 main of every unit and integration test executable.
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
