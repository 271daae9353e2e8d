#include "core/PreviewImage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace gpudem {

namespace {

constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kWallBlue{40, 90, 200};
constexpr Rgb kToolOrange{230, 120, 20}, kPathRed{210, 20, 20};
/// Material colours, cycled.
constexpr Rgb kMaterialColours[] = {{150, 110, 70}, {90, 150, 90},  {120, 120, 190},
                                    {190, 150, 60}, {160, 90, 140}, {90, 160, 170}};

// --- PNG -------------------------------------------------------------------------------------

std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

/// A PNG chunk: length, type, data, CRC of type and data.
void chunk(std::vector<std::uint8_t>& out, const char* type,
           const std::vector<std::uint8_t>& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  std::vector<std::uint8_t> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  put32(out, crc32(body.data(), body.size()));
}

/// A zlib stream of stored (uncompressed) deflate blocks with its Adler-32 (RFC 1950/1951).
std::vector<std::uint8_t> zlib_stored(const std::vector<std::uint8_t>& raw) {
  std::vector<std::uint8_t> z = {0x78, 0x01};
  std::size_t at = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    const bool last = at + n == raw.size();
    z.push_back(last ? 1 : 0);
    const std::uint16_t len = static_cast<std::uint16_t>(n), nlen = static_cast<std::uint16_t>(~n);
    z.insert(z.end(), {static_cast<std::uint8_t>(len), static_cast<std::uint8_t>(len >> 8),
                       static_cast<std::uint8_t>(nlen), static_cast<std::uint8_t>(nlen >> 8)});
    z.insert(z.end(), raw.begin() + at, raw.begin() + at + n);
    at += n;
  } while (at < raw.size());
  std::uint32_t a = 1, b = 0;
  for (std::uint8_t byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  put32(z, (b << 16) | a);
  return z;
}

// --- views -----------------------------------------------------------------------------------

/// One orthographic panel: screen axes u (right) and v (up) from world axes, seen from
/// `toward_viewer`, the shown rectangle centred in a square of `size` pixels at `left`.
struct View {
  int u, v;
  Vec3 toward_viewer;
  int left, size;
  double lo_u, lo_v, scale;  ///< world lower corner shown and pixels per metre
  double pad_u, pad_v;       ///< pixels left free beside and below the shown rectangle
  void at(Vec3 p, double out[2]) const {
    out[0] = left + pad_u + (axis(p, u) - lo_u) * scale;
    out[1] = size - pad_v - (axis(p, v) - lo_v) * scale;
  }
};

/// The box holding the domain, every mesh vertex and every path, grown by 5 %.
void scene_box(const PreviewContent& c, Vec3& lo, Vec3& hi) {
  lo = c.domain_lo;
  hi = c.domain_hi;
  const auto hold = [&](const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      axis(lo, k) = std::min(axis(lo, k), axis(p, k));
      axis(hi, k) = std::max(axis(hi, k), axis(p, k));
    }
  };
  for (const auto* set : {&c.mesh_start, &c.mesh_end})
    for (const PreviewSurface& s : *set)
      for (const Vec3& p : s.vertices) hold(p);
  for (const auto& path : c.paths)
    for (const Vec3& p : path) hold(p);
  const Vec3 margin = 0.05 * (hi - lo);
  lo = lo - margin;
  hi = hi + margin;
}

View make_view(int u, int v, Vec3 toward_viewer, int index, int size, Vec3 lo, Vec3 hi) {
  const double along_u = axis(hi, u) - axis(lo, u), along_v = axis(hi, v) - axis(lo, v);
  const double extent = std::max(along_u, along_v);
  const double scale = extent > 0 ? size / extent : 1.0;
  return {u,
          v,
          toward_viewer,
          index * size,
          size,
          axis(lo, u),
          axis(lo, v),
          scale,
          (size - along_u * scale) / 2,
          (size - along_v * scale) / 2};
}

void draw_particles(Canvas& canvas, const View& view, const PreviewContent& c) {
  std::vector<std::size_t> order(c.centres.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return dot(c.centres[a], view.toward_viewer) < dot(c.centres[b], view.toward_viewer);
  });
  constexpr std::size_t kColours = sizeof(kMaterialColours) / sizeof(kMaterialColours[0]);
  for (std::size_t i : order) {
    double p[2];
    view.at(c.centres[i], p);
    const double r = std::max(0.5, c.radius[i] * view.scale);
    const Rgb colour = kMaterialColours[c.material[i] % kColours];
    canvas.fill_circle(
        p[0], p[1], r,
        {static_cast<std::uint8_t>(colour.r * 0.6), static_cast<std::uint8_t>(colour.g * 0.6),
         static_cast<std::uint8_t>(colour.b * 0.6)});
    canvas.fill_circle(p[0], p[1], std::max(0.5, r - 1), colour);
  }
}

/// Filled triangles, shaded by how squarely each faces the viewer.
void fill_surface(Canvas& canvas, const View& view, const PreviewSurface& s, Rgb colour,
                  double alpha) {
  for (const auto& t : s.triangles) {
    const Vec3 a = s.vertices[t[0]], b = s.vertices[t[1]], c = s.vertices[t[2]];
    const Vec3 n = cross(b - a, c - a);
    const double facing = norm(n) > 0 ? std::abs(dot(n, view.toward_viewer)) / norm(n) : 0;
    const double shade = 0.55 + 0.45 * facing;
    const Rgb lit{static_cast<std::uint8_t>(colour.r * shade),
                  static_cast<std::uint8_t>(colour.g * shade),
                  static_cast<std::uint8_t>(colour.b * shade)};
    double pa[2], pb[2], pc[2];
    view.at(a, pa), view.at(b, pb), view.at(c, pc);
    canvas.fill_triangle(pa, pb, pc, lit, alpha);
  }
}

void draw_polyline(Canvas& canvas, const View& view, const std::vector<Vec3>& points, Rgb c,
                   bool closed) {
  for (std::size_t k = 0; k + 1 < points.size() + (closed ? 1 : 0); ++k) {
    double a[2], b[2];
    view.at(points[k], a), view.at(points[(k + 1) % points.size()], b);
    canvas.draw_line(a, b, c);
  }
}

void draw_box(Canvas& canvas, const View& view, Vec3 lo, Vec3 hi) {
  Vec3 corners[4] = {lo, lo, hi, hi};
  axis(corners[1], view.u) = axis(hi, view.u);
  axis(corners[3], view.u) = axis(lo, view.u);
  draw_polyline(canvas, view, {corners, corners + 4}, kBlack, true);
}

void draw_view(Canvas& canvas, const View& view, const PreviewContent& c) {
  draw_particles(canvas, view, c);
  for (const PreviewSurface& wall : c.walls)  // the fan's rim: vertices 1 … n
    draw_polyline(canvas, view, {wall.vertices.begin() + 1, wall.vertices.end()}, kWallBlue, true);
  draw_box(canvas, view, c.domain_lo, c.domain_hi);
  for (const PreviewSurface& s : c.mesh_end) fill_surface(canvas, view, s, kToolOrange, 0.3);
  for (const PreviewSurface& s : c.mesh_start) fill_surface(canvas, view, s, kToolOrange, 1);
  for (const auto& path : c.paths) draw_polyline(canvas, view, path, kPathRed, false);
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb background)
    : width_(width),
      height_(height),
      pixels_(static_cast<std::size_t>(width) * height, background) {}

void Canvas::blend(int x, int y, Rgb c, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  Rgb& p = pixels_[static_cast<std::size_t>(y) * width_ + x];
  const auto mix = [alpha](std::uint8_t under, std::uint8_t over) {
    return static_cast<std::uint8_t>(std::lround(under + alpha * (over - under)));
  };
  p = {mix(p.r, c.r), mix(p.g, c.g), mix(p.b, c.b)};
}

void Canvas::fill_circle(double cx, double cy, double radius, Rgb c) {
  for (int y = static_cast<int>(std::floor(cy - radius)); y <= cy + radius; ++y)
    for (int x = static_cast<int>(std::floor(cx - radius)); x <= cx + radius; ++x)
      if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) <= radius * radius)
        blend(x, y, c);
}

void Canvas::fill_triangle(const double a[2], const double b[2], const double c[2], Rgb colour,
                           double alpha) {
  const auto edge = [](const double* p, const double* q, double x, double y) {
    return (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
  };
  const int x0 = static_cast<int>(std::floor(std::min({a[0], b[0], c[0]})));
  const int x1 = static_cast<int>(std::ceil(std::max({a[0], b[0], c[0]})));
  const int y0 = static_cast<int>(std::floor(std::min({a[1], b[1], c[1]})));
  const int y1 = static_cast<int>(std::ceil(std::max({a[1], b[1], c[1]})));
  for (int y = std::max(y0, 0); y <= std::min(y1, height_ - 1); ++y)
    for (int x = std::max(x0, 0); x <= std::min(x1, width_ - 1); ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double e0 = edge(a, b, px, py), e1 = edge(b, c, px, py), e2 = edge(c, a, px, py);
      if ((e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0))
        blend(x, y, colour, alpha);
    }
}

void Canvas::draw_line(const double a[2], const double b[2], Rgb c) {
  const double steps = std::max({std::abs(b[0] - a[0]), std::abs(b[1] - a[1]), 1.0});
  for (int k = 0; k <= steps; ++k) {
    const double t = k / steps;
    blend(static_cast<int>(std::floor(a[0] + t * (b[0] - a[0]))),
          static_cast<int>(std::floor(a[1] + t * (b[1] - a[1]))), c);
  }
}

std::vector<std::uint8_t> Canvas::png() const {
  std::vector<std::uint8_t> raw;
  raw.reserve(static_cast<std::size_t>(height_) * (1 + 3 * width_));
  for (int y = 0; y < height_; ++y) {
    raw.push_back(0);  // filter: none
    for (int x = 0; x < width_; ++x) raw.insert(raw.end(), {at(x, y).r, at(x, y).g, at(x, y).b});
  }
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<std::uint8_t> header;
  put32(header, static_cast<std::uint32_t>(width_));
  put32(header, static_cast<std::uint32_t>(height_));
  header.insert(header.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, no filter, no interlace
  chunk(out, "IHDR", header);
  chunk(out, "IDAT", zlib_stored(raw));
  chunk(out, "IEND", {});
  return out;
}

Canvas render_preview(const PreviewContent& content, int panel) {
  Vec3 lo, hi;
  scene_box(content, lo, hi);
  Canvas canvas(3 * panel, panel, kWhite);
  draw_view(canvas, make_view(0, 1, {0, 0, 1}, 0, panel, lo, hi), content);
  draw_view(canvas, make_view(0, 2, {0, -1, 0}, 1, panel, lo, hi), content);
  draw_view(canvas, make_view(1, 2, {1, 0, 0}, 2, panel, lo, hi), content);
  for (int border : {panel, 2 * panel})
    for (int y = 0; y < panel; ++y) canvas.blend(border, y, {200, 200, 200});
  return canvas;
}

}  // namespace gpudem
