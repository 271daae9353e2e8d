#pragma once
/// The PNG of `--preview`: three orthographic views of the scene at t = 0 side by side — from
/// above (x right, y up), from the front (x right, z up, seen along +y) and from the side (y
/// right, z up, seen along −x) — each scaled to the box that holds the domain and every mesh
/// at its start and end pose. Particles are discs coloured by material, drawn far to near; the
/// plane walls' polygons in the domain are outlined in blue, the domain box in black; each mesh
/// is filled in orange at its start pose (over the particles, so a buried tool shows) and in
/// light orange at its end pose, and the path of a moving mesh's centre is a red line. The
/// views hold the paths too, so nothing is drawn into the next panel. Rasterised here and
/// written as an 8-bit RGB PNG (zlib stored blocks; no image library).
#include <cstdint>
#include <string>
#include <vector>

#include "core/PreviewGeometry.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
};

/// An RGB raster, (0, 0) at the top left.
class Canvas {
 public:
  Canvas(int width, int height, Rgb background);
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  /// Mixes colour c into pixel (x, y) with weight alpha; outside the raster, nothing.
  void blend(int x, int y, Rgb c, double alpha = 1);
  /// Pixels whose centre lies within `radius` of (cx, cy).
  void fill_circle(double cx, double cy, double radius, Rgb c);
  /// Pixels whose centre lies in the triangle (either orientation).
  void fill_triangle(const double a[2], const double b[2], const double c[2], Rgb colour,
                     double alpha);
  /// A one-pixel line (DDA).
  void draw_line(const double a[2], const double b[2], Rgb c);
  /// The raster as PNG file bytes.
  std::vector<std::uint8_t> png() const;

 private:
  int width_, height_;
  std::vector<Rgb> pixels_;
};

/// What the preview shows.
struct PreviewContent {
  Vec3 domain_lo, domain_hi;
  std::vector<Vec3> centres;  ///< particle centres [m]
  std::vector<double> radius;
  std::vector<std::uint32_t> material;
  std::vector<PreviewSurface> walls;
  std::vector<PreviewSurface> mesh_start, mesh_end;
  std::vector<std::vector<Vec3>> paths;
};

/// The three views of `content` on one canvas, each panel `panel` pixels square.
Canvas render_preview(const PreviewContent& content, int panel = 600);

}  // namespace gpudem
