#include "wirerig/viewer/application.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "gl.h"
#include "sanitizer_support.h"
#include "wirerig/viewer/headless.h"
#include "wirerig/viewer/image.h"

namespace wirerig {
namespace {

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool ParseInt(const char* text, int* out) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value < 0 || value > 1000000000) return false;
  *out = static_cast<int>(value);
  return true;
}

// Flips rows of a bottom-up RGBA buffer in place.
void FlipRows(Image& image) {
  const std::size_t stride = std::size_t(image.width) * 4;
  std::vector<std::uint8_t> row(stride);
  for (int y = 0; y < image.height / 2; ++y) {
    std::uint8_t* a = image.rgba.data() + std::size_t(y) * stride;
    std::uint8_t* b = image.rgba.data() + std::size_t(image.height - 1 - y) * stride;
    std::memcpy(row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, row.data(), stride);
  }
}

}  // namespace

Result<ApplicationOptions> ParseApplicationOptions(int argc, const char* const* argv,
                                                   ApplicationOptions defaults) {
  ApplicationOptions o = std::move(defaults);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* what) -> const char* {
      if (i + 1 >= argc) return nullptr;
      (void)what;
      return argv[++i];
    };
    if (arg == "--frames") {
      const char* v = value("N");
      if (v == nullptr || !ParseInt(v, &o.frames)) {
        return Error{"--frames needs a whole number of frames in [0, 1000000000]"};
      }
    } else if (arg == "--input") {
      const char* v = value("SCRIPT");
      if (v == nullptr) return Error{"--input needs a script file"};
      o.input_script = v;
    } else if (arg == "--screenshot") {
      const char* v = value("PNG");
      if (v == nullptr) return Error{"--screenshot needs a .png path"};
      o.screenshot = v;
    } else if (arg == "--size") {
      const char* v = value("WxH");
      int w = 0, h = 0;
      if (v == nullptr || std::sscanf(v, "%dx%d", &w, &h) != 2 || w < 16 || h < 16 || w > 8192 ||
          h > 8192) {
        return Error{"--size needs WIDTHxHEIGHT in pixels, each in 16..8192"};
      }
      o.size = {w, h};
    } else if (arg == "--no-window") {
      o.no_window = true;
    } else {
      return Error{"unknown argument '" + arg +
                   "' (--frames N, --input SCRIPT, --screenshot PNG, --size WxH, --no-window)"};
    }
  }
  return o;
}

// The window or headless context behind Run().
struct Application::Platform {
  Application* app = nullptr;
  GLFWwindow* window = nullptr;
  bool glfw = false;
  bool imgui = false;
  std::unique_ptr<HeadlessRenderer> headless;
  bool scripted = false;  // real input is ignored while a script drives the application

  ~Platform() {
    if (imgui) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    if (window != nullptr) glfwDestroyWindow(window);
    if (glfw) glfwTerminate();
  }

  static Application* From(GLFWwindow* w) {
    return static_cast<Platform*>(glfwGetWindowUserPointer(w))->app;
  }
  static bool Ignored(GLFWwindow* w, bool mouse) {
    auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(w));
    if (p->scripted) return true;
    if (!p->imgui) return false;
    const ImGuiIO& io = ImGui::GetIO();
    return mouse ? io.WantCaptureMouse : io.WantCaptureKeyboard;
  }
  // Window coordinates to framebuffer pixels (they differ on high-DPI displays).
  static Vec2f ToPixels(GLFWwindow* w, double x, double y) {
    int ww = 1, wh = 1, fw = 1, fh = 1;
    glfwGetWindowSize(w, &ww, &wh);
    glfwGetFramebufferSize(w, &fw, &fh);
    return Vec2f(float(x) * float(fw) / float(std::max(ww, 1)),
                 float(y) * float(fh) / float(std::max(wh, 1)));
  }

  Result<bool> CreateWindow(const ApplicationOptions& options) {
    glfwSetErrorCallback([](int code, const char* text) {
      std::fprintf(stderr, "GLFW error %d: %s\n", code, text);
    });
    if (glfwInit() != GLFW_TRUE) {
      return Error{
          "cannot open a window: GLFW does not initialise (no display? run under "
          "xvfb-run -a, or pass --no-window)"};
    }
    glfw = true;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, 4);
    window = glfwCreateWindow(options.size.width, options.size.height, options.title.c_str(),
                              nullptr, nullptr);
    if (window == nullptr) {
      return Error{"cannot open a window with an OpenGL 3.3 core context"};
    }
    glfwMakeContextCurrent(window);
    PinLoadedLibrariesForLeakChecks();
    glfwSwapInterval(options.frames > 0 ? 0 : 1);
    glfwSetWindowUserPointer(window, this);
    // Ours first: ImGui's backend chains to callbacks installed before it.
    // The cursor is always tracked (so drags have no jump); presses ImGui takes never start
    // a drag, orbit or pan.
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
      if (static_cast<Platform*>(glfwGetWindowUserPointer(w))->scripted) return;
      From(w)->MouseMove(ToPixels(w, x, y));
    });
    glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int mods) {
      const bool pressed = action == GLFW_PRESS;
      if (pressed && Ignored(w, true)) return;
      if (static_cast<Platform*>(glfwGetWindowUserPointer(w))->scripted) return;
      MouseButton b = MouseButton::kLeft;
      if (button == GLFW_MOUSE_BUTTON_RIGHT)
        b = MouseButton::kRight;
      else if (button == GLFW_MOUSE_BUTTON_MIDDLE)
        b = MouseButton::kMiddle;
      else if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
      From(w)->MouseButtonEvent(b, pressed, (mods & GLFW_MOD_SHIFT) != 0);
    });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
      if (!Ignored(w, true)) From(w)->Scroll(float(dy));
    });
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
      if (Ignored(w, false)) return;
      Application* a = From(w);
      const char fly[6] = {'W', 'A', 'S', 'D', 'Q', 'E'};
      for (int k = 0; k < 6; ++k) {
        if (key == fly[k] && action != GLFW_REPEAT) a->keys_held_[k] = action == GLFW_PRESS;
      }
      if (action != GLFW_PRESS) return;
      if (key == GLFW_KEY_ESCAPE)
        a->Key(27);
      else if (key == GLFW_KEY_SPACE)
        a->Key(' ');
      else if (key == 'F' || key == 'Z')
        a->Key(key);
    });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui = true;
    return true;
  }

  Result<bool> CreateHeadless() {
    Result<std::unique_ptr<HeadlessRenderer>> h = HeadlessRenderer::Create();
    if (!h) return Error{h.error()};
    headless = std::move(h).value();
    return true;
  }
};

Application::Application() = default;
Application::~Application() = default;

int Application::Run(int argc, const char* const* argv) {
  Result<ApplicationOptions> options = ParseApplicationOptions(argc, argv, options_);
  if (!options) {
    std::fprintf(stderr, "%s: %s\n", argc > 0 ? argv[0] : "viewer", options.error().c_str());
    return 1;
  }
  Result<bool> ran = Run(options.value());
  if (!ran) {
    std::fprintf(stderr, "%s: %s\n", argc > 0 ? argv[0] : "viewer", ran.error().c_str());
    return 1;
  }
  return 0;
}

Result<bool> Application::Run(const ApplicationOptions& options) {
  options_ = options;
  size_ = options.size;
  std::vector<InputEvent> script;
  if (!options.input_script.empty()) {
    Result<std::vector<InputEvent>> loaded = LoadInputScript(options.input_script);
    if (!loaded) return Error{loaded.error()};
    script = std::move(loaded).value();
  }

  Platform platform;
  platform.app = this;
  platform.scripted = !options.input_script.empty();
  Result<bool> created =
      options.no_window ? platform.CreateHeadless() : platform.CreateWindow(options);
  if (!created) return Error{created.error()};
  Renderer* renderer = nullptr;
  if (platform.headless) {
    renderer = &platform.headless->renderer();
  } else {
    Result<std::unique_ptr<Renderer>> r = Renderer::Create();
    if (!r) return Error{r.error()};
    renderer_ = std::move(r).value();
    renderer = renderer_.get();
  }
  // Everything GL-owned by the application goes before the context does.
  struct ReleaseRenderer {
    Application* app;
    ~ReleaseRenderer() { app->renderer_.reset(); }
  } release_renderer{this};

  if (Result<bool> initialized = OnInitialize(); !initialized) return initialized;
  frame_ = RenderFrame{};
  OnDisplay(frame_);
  if (!camera_framed_) FrameModel();

  std::size_t next_event = 0;
  double accumulator = 0.0;
  Clock::time_point last = Clock::now();
  Image screenshot;
  for (int frame = 0;; ++frame) {
    if (options.frames > 0 && frame >= options.frames) break;
    if (quit_ || (platform.window != nullptr && glfwWindowShouldClose(platform.window))) break;
    const bool last_frame = options.frames > 0 && frame + 1 == options.frames;

    // Input.
    if (platform.window != nullptr) {
      glfwPollEvents();
      int w = 0, h = 0;
      glfwGetFramebufferSize(platform.window, &w, &h);
      if (w > 0 && h > 0) size_ = {w, h};
    }
    while (next_event < script.size() && script[next_event].frame <= frame) {
      HandleEvent(script[next_event++]);
    }

    // Fixed steps: exactly one per frame for reproducible --frames runs, else by wall time.
    const double wall_ms = MillisecondsSince(last);
    last = Clock::now();
    statistics_.frame_ms = frame == 0 ? wall_ms : 0.9 * statistics_.frame_ms + 0.1 * wall_ms;
    int steps = 1;
    if (options.frames == 0) {
      accumulator += std::min(wall_ms * 1e-3, 0.25);
      steps = int(accumulator / options.fixed_step);
      accumulator -= steps * options.fixed_step;
    }
    const Clock::time_point evaluation_start = Clock::now();
    for (int s = 0; s < steps; ++s) {
      Fly(options.fixed_step);
      timeline_.Advance(options.fixed_step);
      OnUpdate(options.fixed_step);
    }
    frame_ = RenderFrame{};
    OnDisplay(frame_);
    statistics_.evaluation_ms = MillisecondsSince(evaluation_start);

    // Render.
    const Clock::time_point render_start = Clock::now();
    if (platform.headless) {
      if (last_frame && !options.screenshot.empty()) {
        Result<bool> ok =
            platform.headless->RenderToImage(frame_, camera_, size_, &screenshot, render_options_);
        if (!ok) return Error{ok.error()};
      } else {
        platform.headless->RenderAndFinish(frame_, camera_, size_, render_options_);
      }
    } else {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      renderer->Render(frame_, camera_, size_, render_options_);
    }
    statistics_.render_ms = MillisecondsSince(render_start);
    statistics_.render = renderer->stats();

    if (platform.imgui) {
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      DrawHud();
      DrawTimeline(timeline_);
      OnGui();
      ImGui::Render();
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
    if (platform.window != nullptr) {
      if (last_frame && !options.screenshot.empty()) {
        screenshot.width = size_.width;
        screenshot.height = size_.height;
        screenshot.rgba.resize(std::size_t(size_.width) * std::size_t(size_.height) * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, size_.width, size_.height, GL_RGBA, GL_UNSIGNED_BYTE,
                     screenshot.rgba.data());
        FlipRows(screenshot);
      }
      glfwSwapBuffers(platform.window);
    }
    statistics_.frame = frame + 1;
  }
  if (!options.screenshot.empty() && !screenshot.rgba.empty()) {
    Result<std::filesystem::path> saved = SavePng(screenshot, options.screenshot);
    if (!saved) return Error{saved.error()};
  }
  OnShutdown();
  if (std::string failure = Failure(); !failure.empty()) return Error{std::move(failure)};
  return true;
}

void Application::FrameModel() {
  const FrameBounds bounds = ComputeFrameBounds(frame_);
  if (bounds.empty) return;
  FrameCamera(camera_, bounds, size_.Aspect(), 1.25f);
  camera_framed_ = true;
}

void Application::HandleEvent(const InputEvent& e) {
  const Vec2f window(float(size_.width), float(size_.height));
  switch (e.type) {
    case InputEventType::kMove:
      MouseMove(Vec2f(e.x, e.y).cwiseProduct(window));
      break;
    case InputEventType::kMoveBy:
      MouseMove(mouse_ + Vec2f(e.x, e.y).cwiseProduct(window));
      break;
    case InputEventType::kMoveToWire: {
      for (const RenderPolyline& line : frame_.polylines) {
        if (line.id != e.wire) continue;
        Vec2f pixel;
        if (ProjectToPixel(camera_, size_, PointAtParameter(line, e.x), &pixel)) MouseMove(pixel);
        return;
      }
      std::fprintf(stderr, "input script: frame %d: no wire with id %u on screen\n", e.frame,
                   e.wire);
      break;
    }
    case InputEventType::kMoveToGizmo: {
      Vec2f pixel;
      if (GizmoPixel(e.axis, e.x, &pixel)) {
        MouseMove(pixel);
      } else {
        std::fprintf(stderr, "input script: frame %d: no gizmo ring %c on screen\n", e.frame,
                     "xyz"[std::clamp(e.axis, 0, 2)]);
      }
      break;
    }
    case InputEventType::kPress:
    case InputEventType::kRelease:
      MouseButtonEvent(e.button, e.type == InputEventType::kPress, false);
      break;
    case InputEventType::kScroll:
      Scroll(e.y);
      break;
    case InputEventType::kKey: {
      const char fly[6] = {'W', 'A', 'S', 'D', 'Q', 'E'};
      const float tap = 0.1f * camera_.distance;
      const Vec3f moves[6] = {tap * camera_.Forward(),  -tap * camera_.Right(),
                              -tap * camera_.Forward(), tap * camera_.Right(),
                              -tap * Vec3f::UnitY(),    tap * Vec3f::UnitY()};
      for (int k = 0; k < 6; ++k) {
        if (e.key == fly[k]) camera_.target += moves[k];
      }
      Key(e.key);
      break;
    }
  }
}

void Application::MouseMove(const Vec2f& pixel) {
  const Vec2f delta = pixel - mouse_;
  mouse_ = pixel;
  if (handling_) {
    OnHandleDrag(pixel);
  } else if (grabbing_) {
    OnWireDrag(grab_, DragPoint(camera_, size_, pixel, grab_.point));
  } else if (panning_) {
    const float metres_per_pixel =
        camera_.distance * 2.0f * std::tan(0.5f * camera_.fov_y) / float(std::max(size_.height, 1));
    camera_.target += metres_per_pixel * (-delta.x() * camera_.Right() + delta.y() * camera_.Up());
  } else if (orbiting_) {
    camera_.yaw -= 0.008f * delta.x();
    camera_.pitch = std::clamp(camera_.pitch + 0.008f * delta.y(), -1.5f, 1.5f);
  }
}

void Application::MouseButtonEvent(MouseButton button, bool pressed, bool shift) {
  buttons_[int(button)] = pressed;
  if (!pressed) {
    if (handling_ && button == MouseButton::kLeft) {
      handling_ = false;
      OnHandleRelease();
    }
    if (grabbing_ && button == MouseButton::kLeft) {
      grabbing_ = false;
      OnWireRelease();
    }
    orbiting_ = orbiting_ && button != MouseButton::kLeft;
    panning_ = false;
    return;
  }
  if (button == MouseButton::kLeft && !shift) {
    if (OnHandlePress(mouse_)) {
      handling_ = true;
      return;
    }
    const WirePick pick = PickPolyline(frame_.polylines, camera_, size_, mouse_);
    if (pick.hit) {
      grabbing_ = true;
      grab_ = pick;
      statistics_.picks += 1;
      OnWireGrab(pick);
    } else {
      orbiting_ = true;
    }
  } else {
    panning_ = true;
  }
}

void Application::Scroll(float steps) {
  camera_.distance = std::max(1e-4f, camera_.distance * std::pow(0.88f, steps));
}

void Application::Key(int key) {
  switch (key) {
    case 'F':
      FrameModel();
      break;
    case 'Z':
      render_options_.wireframe = !render_options_.wireframe;
      break;
    case ' ':
      timeline_.playing = !timeline_.playing;
      break;
    case 27:
      quit_ = true;
      break;
    default:
      break;
  }
}

void Application::Fly(double dt) {
  const float speed = camera_.distance * float(dt);
  if (keys_held_[0]) camera_.target += speed * camera_.Forward();
  if (keys_held_[1]) camera_.target -= speed * camera_.Right();
  if (keys_held_[2]) camera_.target -= speed * camera_.Forward();
  if (keys_held_[3]) camera_.target += speed * camera_.Right();
  if (keys_held_[4]) camera_.target -= speed * Vec3f::UnitY();
  if (keys_held_[5]) camera_.target += speed * Vec3f::UnitY();
}

void Application::DrawHud() {
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                 ImGuiWindowFlags_NoMove;
  if (ImGui::Begin("HUD", nullptr, flags)) {
    const FrameStatistics& s = statistics_;
    ImGui::Text("frame %.2f ms (%.0f fps)", s.frame_ms,
                s.frame_ms > 0.0 ? 1000.0 / s.frame_ms : 0.0);
    ImGui::Text("evaluation %.2f ms, render %.2f ms", s.evaluation_ms, s.render_ms);
    ImGui::Text("%d vertices, %d triangles", s.render.vertices, s.render.triangles);
    ImGui::Text("%d wires (%d points), %d arrows", s.render.polylines, s.render.polyline_points,
                s.render.arrows);
    ImGui::Checkbox("wireframe (Z)", &render_options_.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("shadows", &render_options_.shadows);
    ImGui::Checkbox("wires", &render_options_.show_wires);
    ImGui::SameLine();
    ImGui::Checkbox("arrows", &render_options_.show_arrows);
    ImGui::TextDisabled("drag a wire to pull it; F frames, WASD/QE fly");
  }
  ImGui::End();
}

bool DrawTimeline(Timeline& timeline) {
  if (timeline.duration <= 0.0) return false;
  const ImGuiIO& io = ImGui::GetIO();
  const float height = 64.0f;
  ImGui::SetNextWindowPos(ImVec2(10.0f, io.DisplaySize.y - height - 10.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(io.DisplaySize.x - 20.0f, height), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.55f);
  bool moved = false;
  const ImGuiWindowFlags flags =
      ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;
  if (ImGui::Begin("Timeline", nullptr, flags)) {
    if (ImGui::Button(timeline.playing ? "Pause" : "Play", ImVec2(60.0f, 0.0f))) {
      timeline.playing = !timeline.playing;
    }
    ImGui::SameLine();
    ImGui::Checkbox("loop", &timeline.loop);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    float speed = float(timeline.speed);
    if (ImGui::SliderFloat("speed", &speed, -2.0f, 4.0f, "%.2fx")) timeline.speed = speed;
    ImGui::SameLine();
    ImGui::Text("t = %.3f / %.3f s", timeline.time, timeline.duration);
    ImGui::SetNextItemWidth(-1.0f);
    float t = float(timeline.time);
    if (ImGui::SliderFloat("##time", &t, 0.0f, float(timeline.duration), "")) {
      timeline.Seek(t);
      moved = true;
    }
    // Key ticks over the scrub bar.
    const ImVec2 lo = ImGui::GetItemRectMin();
    const ImVec2 hi = ImGui::GetItemRectMax();
    const float pad =
        ImGui::GetStyle().GrabMinSize * 0.5f + ImGui::GetStyle().FramePadding.x * 0.5f;
    ImDrawList* draw = ImGui::GetWindowDrawList();
    for (double key : timeline.keys) {
      const float f = float(std::clamp(key / timeline.duration, 0.0, 1.0));
      const float x = lo.x + pad + f * (hi.x - lo.x - 2.0f * pad);
      draw->AddLine(ImVec2(x, lo.y), ImVec2(x, lo.y + 5.0f), IM_COL32(255, 210, 80, 255), 2.0f);
      draw->AddLine(ImVec2(x, hi.y - 5.0f), ImVec2(x, hi.y), IM_COL32(255, 210, 80, 255), 2.0f);
    }
  }
  ImGui::End();
  return moved;
}

}  // namespace wirerig
