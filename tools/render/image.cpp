#include "image.hpp"

#include <algorithm>
#include <cstdlib>

namespace ugv::render {

Image::Image(int width, int height, Rgb fill) : w_(width), h_(height), px_(static_cast<std::size_t>(width * height) * 3)
{
    fill_rect(0, 0, width - 1, height - 1, fill);
}

Rgb Image::at(int x, int y) const
{
    const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)) * 3;
    return {px_[k], px_[k + 1], px_[k + 2]};
}

void Image::set(int x, int y, Rgb c)
{
    if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
    const std::size_t k = (static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) + static_cast<std::size_t>(x)) * 3;
    px_[k] = c.r;
    px_[k + 1] = c.g;
    px_[k + 2] = c.b;
}

void Image::fill_rect(int x0, int y0, int x1, int y1, Rgb c)
{
    for (int y = std::max(0, std::min(y0, y1)); y <= std::min(h_ - 1, std::max(y0, y1)); ++y)
        for (int x = std::max(0, std::min(x0, x1)); x <= std::min(w_ - 1, std::max(x0, x1)); ++x) set(x, y, c);
}

void Image::line(int x0, int y0, int x1, int y1, Rgb c)
{
    // Bresenham.
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (;;) {
        set(x0, y0, c);
        if (x0 == x1 && y0 == y1) break;
        const int e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

namespace {

// 3x5 glyphs, one row per 3-bit value, top to bottom.
const uint8_t* glyph(char ch)
{
    static const uint8_t digits[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7},
                                          {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1},
                                          {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
    static const uint8_t dot[5] = {0, 0, 0, 0, 2}, minus[5] = {0, 0, 7, 0, 0}, plus[5] = {0, 2, 7, 2, 0};
    static const uint8_t m[5] = {0, 0, 7, 7, 5}, z[5] = {0, 7, 1, 2, 7}, v[5] = {0, 5, 5, 5, 2};
    static const uint8_t a[5] = {0, 6, 1, 7, 7}, r[5] = {0, 6, 5, 4, 4}, two_up[5] = {6, 2, 6, 0, 0};
    static const uint8_t blank[5] = {0, 0, 0, 0, 0};
    // Capitals, for legends; a small letter without its own glyph below is drawn as its capital.
    static const uint8_t letters[26][5] = {
        {2, 5, 7, 5, 5}, {6, 5, 6, 5, 6}, {3, 4, 4, 4, 3}, {6, 5, 5, 5, 6}, {7, 4, 6, 4, 7}, {7, 4, 6, 4, 4},
        {3, 4, 5, 5, 3}, {5, 5, 7, 5, 5}, {7, 2, 2, 2, 7}, {1, 1, 1, 5, 2}, {5, 5, 6, 5, 5}, {4, 4, 4, 4, 7},
        {5, 7, 7, 5, 5}, {6, 5, 5, 5, 5}, {2, 5, 5, 5, 2}, {6, 5, 6, 4, 4}, {2, 5, 5, 6, 3}, {6, 5, 6, 5, 5},
        {3, 4, 2, 1, 6}, {7, 2, 2, 2, 2}, {5, 5, 5, 5, 7}, {5, 5, 5, 5, 2}, {5, 5, 7, 7, 5}, {5, 5, 2, 5, 5},
        {5, 5, 2, 2, 2}, {7, 1, 2, 4, 7}};
    static const uint8_t colon[5] = {0, 2, 0, 2, 0}, slash[5] = {1, 1, 2, 4, 4}, open[5] = {1, 2, 2, 2, 1},
                         close[5] = {4, 2, 2, 2, 4}, equals[5] = {0, 7, 0, 7, 0}, comma[5] = {0, 0, 0, 2, 4};
    if (ch >= '0' && ch <= '9') return digits[ch - '0'];
    if (ch >= 'A' && ch <= 'Z') return letters[ch - 'A'];
    switch (ch) {
        case '.': return dot;
        case '-': return minus;
        case '+': return plus;
        case 'm': return m;
        case 'z': return z;
        case 'v': return v;
        case 'a': return a;
        case 'r': return r;
        case '^': return two_up;  // "m^" renders as m with a superscript 2
        case ':': return colon;
        case '/': return slash;
        case '(': return open;
        case ')': return close;
        case '=': return equals;
        case ',': return comma;
        default: return ch >= 'a' && ch <= 'z' ? letters[ch - 'a'] : blank;
    }
}

}  // namespace

void Image::text(int x, int y, const std::string& s, Rgb c, int scale)
{
    for (char ch : s) {
        const uint8_t* g = glyph(ch);
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col)
                if (g[row] & (4 >> col))
                    fill_rect(x + col * scale, y + row * scale, x + (col + 1) * scale - 1, y + (row + 1) * scale - 1, c);
        x += 4 * scale;
    }
}

}  // namespace ugv::render
