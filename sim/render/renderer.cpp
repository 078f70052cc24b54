#define GL_GLEXT_PROTOTYPES 1
#include "sim/render/renderer.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "sim/render/texture.h"

namespace coopmap::sim {

namespace {
struct Vertex {
  float x, y, z, u, v;
  unsigned char r, g, b, a;  // flat per-face shade, modulating the texture
};

// A flat shade per face from a fixed light, so faces of one texture stay distinguishable.
float faceShade(const Eigen::Vector3d& n) {
  const Eigen::Vector3d light = Eigen::Vector3d(0.4, 0.3, 0.86).normalized();
  return static_cast<float>(0.7 + 0.3 * std::abs(n.dot(light)));
}

// Appends a quad (a, b, c, d counter-clockwise) with world-scaled texture coordinates.
void addQuad(std::vector<Vertex>& out, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& c, const Eigen::Vector3d& d, const Eigen::Vector2d& ta,
             const Eigen::Vector2d& tb, const Eigen::Vector2d& tc, const Eigen::Vector2d& td,
             double tile) {
  const auto s = static_cast<unsigned char>(255.0f * faceShade((b - a).cross(d - a).normalized()));
  auto v = [&](const Eigen::Vector3d& p, const Eigen::Vector2d& t) {
    out.push_back({float(p.x()), float(p.y()), float(p.z()), float(t.x() / tile),
                   float(t.y() / tile), s, s, s, 255});
  };
  v(a, ta), v(b, tb), v(c, tc), v(a, ta), v(c, tc), v(d, td);
}

void addBox(std::vector<Vertex>& out, const SolidBox& box, double tile) {
  const double c = std::cos(box.yaw), s = std::sin(box.yaw);
  const Eigen::Vector2d ax(c, s), ay(-s, c);
  const double hx = 0.5 * box.size.x(), hy = 0.5 * box.size.y();
  const double z0 = box.z0, z1 = box.z0 + box.size.z();
  Eigen::Vector2d corner[4] = {box.center - hx * ax - hy * ay, box.center + hx * ax - hy * ay,
                               box.center + hx * ax + hy * ay, box.center - hx * ax + hy * ay};
  double along = 0.0;  // texture u runs around the box so textures continue over edges
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d p = corner[i], q = corner[(i + 1) % 4];
    const double len = (q - p).norm();
    addQuad(out, {p.x(), p.y(), z0}, {q.x(), q.y(), z0}, {q.x(), q.y(), z1}, {p.x(), p.y(), z1},
            {along, z0}, {along + len, z0}, {along + len, z1}, {along, z1}, tile);
    along += len;
  }
  auto xy = [](const Eigen::Vector2d& p) { return p; };
  addQuad(out, {corner[0].x(), corner[0].y(), z1}, {corner[1].x(), corner[1].y(), z1},
          {corner[2].x(), corner[2].y(), z1}, {corner[3].x(), corner[3].y(), z1}, xy(corner[0]),
          xy(corner[1]), xy(corner[2]), xy(corner[3]), tile);
}

void addCylinder(std::vector<Vertex>& out, const DynamicCylinder& cyl, double tile) {
  constexpr int kSides = 16;
  for (int i = 0; i < kSides; ++i) {
    const double a0 = 2 * M_PI * i / kSides, a1 = 2 * M_PI * (i + 1) / kSides;
    const Eigen::Vector2d p = cyl.center + cyl.radius * Eigen::Vector2d(std::cos(a0), std::sin(a0));
    const Eigen::Vector2d q = cyl.center + cyl.radius * Eigen::Vector2d(std::cos(a1), std::sin(a1));
    const double u0 = cyl.radius * a0, u1 = cyl.radius * a1;
    addQuad(out, {p.x(), p.y(), 0}, {q.x(), q.y(), 0}, {q.x(), q.y(), cyl.height},
            {p.x(), p.y(), cyl.height}, {u0, 0}, {u1, 0}, {u1, cyl.height}, {u0, cyl.height}, tile);
  }
}
}  // namespace

struct Renderer::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;
  struct Batch {
    GLuint texture = 0;
    double tile = 1.0;
    std::vector<Vertex> vertices;
    GLuint buffer = 0;  // vertices uploaded once to a buffer object
  };
  std::map<std::string, Batch> batches;  // static geometry per texture
  GLuint dynamic_texture = 0;
  double dynamic_tile = 0.5;
  std::vector<Vertex> dynamic_vertices;
  std::vector<float> depth_buffer;
  cv::Mat red;
  double near_m = 0.05, far_m = 60.0;

  GLuint upload(const cv::Mat& img) {
    GLuint id = 0;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE8, img.cols, img.rows, 0, GL_LUMINANCE,
                 GL_UNSIGNED_BYTE, img.data);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return id;
  }

  // Draws vertices from client memory (base != nullptr) or the bound buffer (base == 0).
  static void draw(const Vertex* base, size_t count) {
    if (count == 0) return;
    // GL takes a bound buffer's offsets as pointers: computed as integers, since adding an
    // offset to a null pointer is undefined behaviour.
    const uintptr_t p = reinterpret_cast<uintptr_t>(base);
    auto at = [p](size_t offset) { return reinterpret_cast<const void*>(p + offset); };
    glVertexPointer(3, GL_FLOAT, sizeof(Vertex), at(offsetof(Vertex, x)));
    glTexCoordPointer(2, GL_FLOAT, sizeof(Vertex), at(offsetof(Vertex, u)));
    glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), at(offsetof(Vertex, r)));
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(count));
  }
};

Renderer::Renderer(const World& world, const CameraIntrinsics& k, double near_m, double far_m)
    : impl_(std::make_unique<Impl>()), intrinsics_(k) {
  Impl& im = *impl_;
  im.near_m = near_m;
  im.far_m = far_m;
  im.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!im.context) throw std::runtime_error("renderer: cannot create an OSMesa context");
  im.buffer.resize(static_cast<size_t>(k.width) * kMaxViews * k.height * 4);
  if (!OSMesaMakeCurrent(im.context, im.buffer.data(), GL_UNSIGNED_BYTE, k.width * kMaxViews,
                         k.height))
    throw std::runtime_error("renderer: OSMesaMakeCurrent failed");
  // Trilinear mipmapping only: anisotropic filtering triples llvmpipe's render time and
  // did not change the maps (measured on worlds/lab.yaml).

  for (const auto& [name, spec] : world.textures) {
    Impl::Batch& b = im.batches[name];
    b.texture = im.upload(makeTexture(spec));
    b.tile = spec.tile;
  }
  // Floor (texture coordinates in world metres, so rectangles that meet match).
  for (const FloorArea& area : world.floorRects()) {
    Impl::Batch& b = im.batches.at(world.floor_texture);
    const Eigen::Vector2d lo = area.min, hi = area.max;
    addQuad(b.vertices, {lo.x(), lo.y(), 0}, {hi.x(), lo.y(), 0}, {hi.x(), hi.y(), 0},
            {lo.x(), hi.y(), 0}, {lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()},
            {lo.x(), hi.y()}, b.tile);
  }
  for (const SolidBox& box : world.solids()) {
    Impl::Batch& b = im.batches.at(box.texture);
    addBox(b.vertices, box, b.tile);
  }
  // Checkerboard targets: one single-sided quad each with its print (texture clamped at the
  // border), counter-clockwise seen from the front (board -z).
  for (size_t t = 0; t < world.targets.size(); ++t) {
    const TargetSpec& target = world.targets[t];
    Impl::Batch& b = im.batches["__target_" + std::to_string(t)];
    b.texture = im.upload(makeCheckerboardTexture(target));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const double hw = (0.5 * target.squares_x + target.border) * target.square;
    const double hh = (0.5 * target.squares_y + target.border) * target.square;
    const Eigen::Matrix3d R = target.rotation();
    auto at = [&](double x, double y) -> Eigen::Vector3d {
      return target.center + R * Eigen::Vector3d(x, y, 0.0);
    };
    addQuad(b.vertices, at(-hw, -hh), at(-hw, hh), at(hw, hh), at(hw, -hh), {0, 0}, {0, 1}, {1, 1},
            {1, 0}, 1.0);
  }
  for (auto& [name, batch] : im.batches) {
    if (batch.vertices.empty()) continue;
    glGenBuffers(1, &batch.buffer);
    glBindBuffer(GL_ARRAY_BUFFER, batch.buffer);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(batch.vertices.size() * sizeof(Vertex)),
                 batch.vertices.data(), GL_STATIC_DRAW);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  TextureSpec robot_skin;
  robot_skin.name = "__robot";
  robot_skin.type = TextureType::kPosters;
  robot_skin.tile = im.dynamic_tile;
  robot_skin.feature = 0.02;
  robot_skin.seed = world.seed ^ 0xB14;
  im.dynamic_texture = im.upload(makeTexture(robot_skin));

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  // Back faces are culled: every solid is closed and its faces wind counter-clockwise seen
  // from outside (the robot never looks out of a solid), a third less to rasterize.
  glCullFace(GL_BACK);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glViewport(0, 0, k.width, k.height);
  glClearColor(0.75f, 0.75f, 0.75f, 1.0f);
}

Renderer::~Renderer() {
  if (impl_ && impl_->context) OSMesaDestroyContext(impl_->context);
}

void Renderer::render(const Eigen::Isometry3d& X_WC, const std::vector<DynamicCylinder>& others,
                      const std::vector<SolidBox>& boxes, cv::Mat& grey, cv::Mat* depth) {
  renderViews({X_WC}, others, boxes, {&grey}, depth);
}

void Renderer::renderViews(const std::vector<Eigen::Isometry3d>& X_WCs,
                           const std::vector<DynamicCylinder>& others,
                           const std::vector<SolidBox>& boxes, const std::vector<cv::Mat*>& greys,
                           cv::Mat* first_depth) {
  Impl& im = *impl_;
  const CameraIntrinsics& k = intrinsics_;
  const int views = static_cast<int>(X_WCs.size());
  if (views < 1 || views > kMaxViews || greys.size() != X_WCs.size())
    throw std::invalid_argument("renderer: 1.." + std::to_string(kMaxViews) +
                                " views with one image each expected");
  if (!OSMesaMakeCurrent(im.context, im.buffer.data(), GL_UNSIGNED_BYTE, k.width * kMaxViews,
                         k.height))
    throw std::runtime_error("renderer: OSMesaMakeCurrent failed");
  const double n = im.near_m, f = im.far_m, W = k.width, H = k.height;
  // Column-major projection mapping OpenCV intrinsics (pixel centres at integers) to GL.
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * k.fx / W;
  P(0, 2) = 1.0 - 2.0 * (k.cx + 0.5) / W;
  P(1, 1) = 2.0 * k.fy / H;
  P(1, 2) = 2.0 * (k.cy + 0.5) / H - 1.0;
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2.0 * f * n / (f - n);
  P(3, 2) = -1.0;
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();  // OpenCV camera -> GL eye
  flip(1, 1) = -1.0;
  flip(2, 2) = -1.0;
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(P.data());
  glViewport(0, 0, k.width * views, k.height);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  // Moving things are built once for all views.
  im.dynamic_vertices.clear();
  for (const DynamicCylinder& c : others) addCylinder(im.dynamic_vertices, c, im.dynamic_tile);
  const size_t cylinder_vertices = im.dynamic_vertices.size();
  std::vector<size_t> box_end;  // one past each box's last vertex
  for (const SolidBox& box : boxes) {
    addBox(im.dynamic_vertices, box, im.batches.at(box.texture).tile);
    box_end.push_back(im.dynamic_vertices.size());
  }
  for (int v = 0; v < views; ++v) {
    glViewport(v * k.width, 0, k.width, k.height);
    const Eigen::Matrix4d V = flip * X_WCs[v].inverse().matrix();
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(V.data());
    for (const auto& [name, batch] : im.batches) {
      if (!batch.buffer) continue;
      glBindTexture(GL_TEXTURE_2D, batch.texture);
      glBindBuffer(GL_ARRAY_BUFFER, batch.buffer);
      Impl::draw(nullptr, batch.vertices.size());
    }
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    if (cylinder_vertices > 0) {
      glBindTexture(GL_TEXTURE_2D, im.dynamic_texture);
      Impl::draw(im.dynamic_vertices.data(), cylinder_vertices);
    }
    size_t at = cylinder_vertices;
    for (size_t b = 0; b < boxes.size(); ++b) {
      glBindTexture(GL_TEXTURE_2D, im.batches.at(boxes[b].texture).texture);
      Impl::draw(im.dynamic_vertices.data() + at, box_end[b] - at);
      at = box_end[b];
    }
  }
  glFinish();

  im.red.create(k.height, k.width * views, CV_8UC1);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, k.width * views, k.height, GL_RED, GL_UNSIGNED_BYTE, im.red.data);
  for (int v = 0; v < views; ++v)
    cv::flip(im.red(cv::Rect(v * k.width, 0, k.width, k.height)), *greys[v], 0);
  if (first_depth) {
    im.depth_buffer.resize(static_cast<size_t>(k.width) * k.height);
    glReadPixels(0, 0, k.width, k.height, GL_DEPTH_COMPONENT, GL_FLOAT, im.depth_buffer.data());
    cv::Mat& depth = *first_depth;
    depth.create(k.height, k.width, CV_32F);
    for (int row = 0; row < k.height; ++row) {
      const float* src = im.depth_buffer.data() + static_cast<size_t>(k.height - 1 - row) * k.width;
      float* dst = depth.ptr<float>(row);
      for (int x = 0; x < k.width; ++x) {
        const double d = src[x];
        if (d >= 1.0) {
          dst[x] = 0.0f;
          continue;
        }
        const double z_ndc = 2.0 * d - 1.0;
        dst[x] = static_cast<float>(2.0 * f * n / ((f + n) - z_ndc * (f - n)));
      }
    }
  }
}

}  // namespace coopmap::sim
