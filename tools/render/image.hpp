// An RGB canvas with the few drawing primitives the map pictures need, and a 3x5 pixel
// font for numbers, units and legends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ugv::render {

struct Rgb
{
    uint8_t r, g, b;
    bool operator==(const Rgb&) const = default;
};

class Image
{
public:
    Image(int width, int height, Rgb fill = {255, 255, 255});
    int width() const { return w_; }
    int height() const { return h_; }
    const std::vector<uint8_t>& rgb() const { return px_; }
    Rgb at(int x, int y) const;
    void set(int x, int y, Rgb c);  // ignored outside
    void fill_rect(int x0, int y0, int x1, int y1, Rgb c);  // inclusive, clipped
    void line(int x0, int y0, int x1, int y1, Rgb c);
    // Text in the 3x5 font (digits, capitals, '.', '-', '+', ':', '/', '(', ')', '=', ',', ' ';
    // 'm', 'z', 'v', 'a', 'r' have small forms, other small letters are drawn as capitals), scaled.
    void text(int x, int y, const std::string& s, Rgb c, int scale = 2);

private:
    int w_, h_;
    std::vector<uint8_t> px_;
};

}  // namespace ugv::render
