// The LMS 2xx variants the emulator can act as (`ugv-sim lms --variant NAME`): what each
// answers to the type (3A), status (31) and configuration (74) requests, its factory
// configuration, and which measuring modes and scan variants it accepts. From the fact sheet
// (shared/protocols/sick-lms2xx.md) where it says; the rest is marked in docs/lms.md,
// "Variants", as the emulator's choice within what the fact sheet allows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ugv::sim::lms {

struct Variant
{
    std::string name;              // "LMS200", as given to --variant
    std::string type_string;       // the 0xBA reply
    std::string software_version;  // the status block's first 7 bytes
    std::size_t status_bytes = 30; // the 0xB1 block's length
    std::size_t config_bytes = 32; // the 0x74 block's length (32-42 by firmware)
    uint8_t factory_units = 0x00;  // config byte 6 at power-on: 0x00 cm, 0x01 mm
    uint8_t factory_measuring_mode = 0x00;  // config byte 5: 0x00 8/80 m, 0x06 32 m
    std::vector<uint8_t> measuring_modes;   // what a configuration write (77) may set
    bool outdoor = false;          // 211/221/291: outdoor housings (fog correction, heating)
};

// Every variant, LMS200 first (the default).
const std::vector<Variant>& variants();
// The variant called name ("LMS291" or "291"); throws std::invalid_argument listing the names.
const Variant& find_variant(const std::string& name);
// "LMS200, LMS211, ...".
std::string variant_names();

// The status block the variant answers with: its software version, then the operating mode
// (0x24 streaming, 0x25 request mode), zero-padded to status_bytes.
std::vector<uint8_t> status_block(const Variant& v, bool streaming);

}  // namespace ugv::sim::lms
