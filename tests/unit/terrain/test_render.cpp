#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>

#include "map_render.hpp"
#include "png_writer.hpp"

using namespace ugv;
using namespace ugv::render;

TEST_CASE("CRC-32 and Adler-32 known answers")
{
    const uint8_t iend[] = {'I', 'E', 'N', 'D'};
    CHECK(crc32(iend, 4) == 0xAE426082u);  // the CRC every PNG ends with
    const char* check = "123456789";
    CHECK(crc32(reinterpret_cast<const uint8_t*>(check), 9) == 0xCBF43926u);
    const char* wiki = "Wikipedia";
    CHECK(adler32(reinterpret_cast<const uint8_t*>(wiki), 9) == 0x11E60398u);
}

TEST_CASE("a 2x1 PNG has the signature, IHDR and one stored deflate block")
{
    const std::vector<uint8_t> rgb = {255, 0, 0, 0, 0, 255};
    const std::vector<uint8_t> png = encode_png(2, 1, rgb);
    const uint8_t sig[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    REQUIRE(png.size() > 8 + 25 + 12);
    CHECK(std::memcmp(png.data(), sig, 8) == 0);
    CHECK(std::memcmp(png.data() + 12, "IHDR", 4) == 0);
    CHECK(png[19] == 2);   // width 2 (big endian, low byte)
    CHECK(png[23] == 1);   // height 1
    CHECK(png[24] == 8);   // bit depth
    CHECK(png[25] == 2);   // colour type RGB
    // IDAT: zlib header 78 01, final stored block of 7 bytes (filter byte + 6), the row, Adler-32.
    const std::size_t idat = 8 + 25;
    CHECK(std::memcmp(png.data() + idat + 4, "IDAT", 4) == 0);
    const uint8_t* z = png.data() + idat + 8;
    CHECK(z[0] == 0x78);
    CHECK(z[1] == 0x01);
    CHECK((z[0] * 256 + z[1]) % 31 == 0);
    CHECK(z[2] == 1);
    CHECK(z[3] == 7);
    CHECK(z[4] == 0);
    CHECK(z[5] == 0xF8);
    CHECK(z[6] == 0xFF);
    CHECK(z[7] == 0);  // filter type none
    CHECK(std::memcmp(z + 8, rgb.data(), 6) == 0);
    const uint8_t raw[] = {0, 255, 0, 0, 0, 0, 255};
    const uint32_t a = adler32(raw, 7);
    CHECK(z[14] == static_cast<uint8_t>(a >> 24));
    CHECK(z[17] == static_cast<uint8_t>(a));
    CHECK(std::memcmp(png.data() + png.size() - 8, "IEND", 4) == 0);
}

TEST_CASE("the plan view: unknown white, elevation coloured, forward up and left left")
{
    terrain_map_t m{};
    m.nx = 20;
    m.ny = 20;
    m.ncells = 400;
    m.resolution = 0.5f;
    m.origin_x = 10.0f;  // the vehicle is drawn outside: this test is about the cells
    m.origin_y = -5.0f;
    m.mean_z.assign(400, NAN);
    m.variance_z.assign(400, NAN);
    m.count.assign(400, 0);
    m.max_z.assign(400, NAN);
    m.min_z.assign(400, NAN);
    m.age_s.assign(400, NAN);
    m.mean_z[19 * 20 + 0] = 1.0f;  // far, rightmost: top right of the picture, the highest (red)
    m.variance_z[19 * 20 + 0] = 0.04f;
    m.mean_z[0 * 20 + 19] = 0.0f;  // near, leftmost: bottom left, the lowest (green)
    m.variance_z[0 * 20 + 19] = 0.0f;
    RenderOptions o;
    o.cell_px = 2;
    o.variance_panel = true;
    const Image img = render_map(m, o);
    int x = 0, y = 0;
    cell_pixel(m, 2, 19, 0, x, y);
    CHECK(y == 10);
    CHECK(x == 10 + 19 * 2);
    CHECK(img.at(x, y) == elevation_colour(1.0));
    CHECK(img.at(x, y) == Rgb{215, 0, 0});
    cell_pixel(m, 2, 0, 19, x, y);
    CHECK(img.at(x, y) == elevation_colour(0.0));
    cell_pixel(m, 2, 5, 5, x, y);
    CHECK(img.at(x, y) == kUnknown);
    // The deviation panel: the 0.2 m cell is the darkest.
    cell_pixel(m, 2, 19, 0, x, y);
    CHECK(img.at(x + 40 + 20, y) == deviation_colour(1.0));
    CHECK(img.at(x + 40 + 20, y + 38) == kUnknown);
    for (double t = 0.0; t <= 1.0; t += 0.05) CHECK_FALSE(elevation_colour(t) == kUnknown);
}

TEST_CASE("the vehicle outline and reference point are drawn where the map says")
{
    terrain_map_t m{};
    m.nx = m.ny = 40;
    m.ncells = 1600;
    m.resolution = 0.25f;
    m.origin_x = -0.5f;  // rear bumper 0.5 m behind the body origin
    m.origin_y = -5.0f;
    m.mean_z.assign(1600, NAN);
    m.variance_z.assign(1600, NAN);
    m.count.assign(1600, 0);
    m.max_z.assign(1600, NAN);
    m.min_z.assign(1600, NAN);
    m.age_s.assign(1600, NAN);
    RenderOptions o;
    o.cell_px = 4;
    const Image img = render_map(m, o);
    // Reference point (body x -0.5, y 0): 10 m - (-0.5 + 0.5... ) -> bottom edge, middle column.
    // far_x = -0.5 + 10 = 9.5; y px = 10 + (9.5 - (-0.5)) / 0.25 * 4 = 170; x px = 10 + (5 - 0) / 0.25 * 4 = 90.
    CHECK(img.at(90, 169) == kReference);
    // The outline's front edge (body x 2.0): y px = 10 + (9.5 - 2.0) / 0.25 * 4 = 130.
    CHECK(img.at(90, 130) == kVehicle);
}

TEST_CASE("the max and min layers colour each cell by its highest or lowest sample")
{
    terrain_map_t m{};
    m.nx = m.ny = 10;
    m.ncells = 100;
    m.resolution = 0.5f;
    m.origin_x = 10.0f;  // the vehicle outside the picture
    m.origin_y = -2.5f;
    m.mean_z.assign(100, NAN);
    m.variance_z.assign(100, NAN);
    m.count.assign(100, 0);
    m.max_z.assign(100, NAN);
    m.min_z.assign(100, NAN);
    m.age_s.assign(100, NAN);
    // Two known cells: a wall's (mean 0.5, samples 0 .. 1.5) and the ground's (mean, max and
    // min 0.1 .. 0.2).
    const std::size_t wall = 3 * 10 + 4, ground = 6 * 10 + 2;
    m.mean_z[wall] = 0.5f;
    m.max_z[wall] = 1.5f;
    m.min_z[wall] = 0.0f;
    m.mean_z[ground] = 0.15f;
    m.max_z[ground] = 0.2f;
    m.min_z[ground] = 0.1f;
    m.variance_z[wall] = m.variance_z[ground] = 0.01f;
    RenderOptions o;
    o.cell_px = 2;
    int wx = 0, wy = 0, gx = 0, gy = 0;
    cell_pixel(m, 2, 3, 4, wx, wy);
    cell_pixel(m, 2, 6, 2, gx, gy);
    // Mean: the wall is highest (red), the ground lowest (green).
    Image img = render_map(m, o);
    CHECK(img.at(wx, wy) == elevation_colour(1.0));
    CHECK(img.at(gx, gy) == elevation_colour(0.0));
    // Max on a fixed scale 0 .. 1.5: the wall's cell is at the top.
    o.layer = Layer::max;
    o.z_min_m = 0.0;
    o.z_max_m = 1.5;
    img = render_map(m, o);
    CHECK(img.at(wx, wy) == elevation_colour(1.0));
    CHECK(img.at(gx, gy) == elevation_colour(0.2 / 1.5));
    // Min on the same scale: the wall's lowest sample is the ground in front of it.
    o.layer = Layer::min;
    img = render_map(m, o);
    CHECK(img.at(wx, wy) == elevation_colour(0.0));
    CHECK(img.at(gx, gy) == elevation_colour(0.1 / 1.5));
    cell_pixel(m, 2, 0, 0, wx, wy);
    CHECK(img.at(wx, wy) == kUnknown);
}

TEST_CASE("--z-span: a fixed scale from the ground under the vehicle, so flat ground has one colour")
{
    // Flat ground 750 m up with 2 cm of noise, one 0.5 m box; then the same ground with a
    // 3 m wall in view.
    terrain_map_t m{};
    m.nx = m.ny = 10;
    m.ncells = 100;
    m.resolution = 0.5f;
    m.origin_x = 10.0f;  // the vehicle outside the picture
    m.origin_y = -2.5f;
    m.pose.position[2] = 750.0;  // the body origin is on the ground
    m.mean_z.assign(100, 750.0f);
    m.variance_z.assign(100, 0.0004f);
    m.count.assign(100, 5);
    m.max_z = m.min_z = m.mean_z;
    const std::size_t low = 2 * 10 + 2, high = 2 * 10 + 3, box = 5 * 10 + 5, far = 9 * 10 + 9;
    m.mean_z[low] = 749.98f;
    m.mean_z[high] = 750.02f;
    m.mean_z[box] = 750.5f;
    RenderOptions o;
    o.cell_px = 2;
    auto colour = [&](const terrain_map_t& map, std::size_t k) {
        int x = 0, y = 0;
        cell_pixel(map, 2, static_cast<int>(k) / 10, static_cast<int>(k) % 10, x, y);
        return render_map(map, o).at(x, y);
    };
    // The complaint: without the box, the automatic scale (at least 0.1 m tall) spreads the
    // 4 cm of noise over 40 % of the colours.
    terrain_map_t bare = m;
    bare.mean_z[box] = 750.0f;
    CHECK(colour(bare, low) == elevation_colour(0.3));
    CHECK(colour(bare, high) == elevation_colour(0.7));
    // 1 m span: from 749.75 to 750.75; the ground a quarter up, the box three quarters.
    o.z_span_m = 1.0;
    CHECK(colour(m, far) == elevation_colour(0.25));
    CHECK(colour(m, box) == elevation_colour(0.75));
    // The noise is 4 % of the scale, in the box's picture and in the bare one alike.
    CHECK(colour(m, low) == elevation_colour(0.23));
    CHECK(colour(m, high) == elevation_colour(0.27));
    CHECK(colour(bare, low) == elevation_colour(0.23));
    CHECK(colour(bare, high) == elevation_colour(0.27));
    // A wall in view does not change the ground's colour (it would on the automatic scale).
    terrain_map_t walled = m;
    walled.mean_z[box] = 753.0f;
    CHECK(colour(walled, far) == elevation_colour(0.25));
    CHECK(colour(walled, box) == elevation_colour(1.0));
    o.z_span_m = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(colour(walled, far) == colour(m, far));
    // The same ground at 1.5 m (another world) in the same colour.
    terrain_map_t other = m;
    for (float& z : other.mean_z) z -= 748.5f;
    other.pose.position[2] = 1.5;
    o.z_span_m = 1.0;
    CHECK(colour(other, far) == colour(m, far));
    CHECK(colour(other, box) == colour(m, box));
}
