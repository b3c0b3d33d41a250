// nephele-view — the window, the frame loop, input, the panel and scripted runs.
#include "viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <chrono>
#include <optional>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "camera_control.h"
#include "dynamic_resolution.h"
#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "panel.h"
#include "path_control.h"
#include "scene_editor.h"
#include "vulkan_window.h"

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace nephele::view {
namespace {


constexpr int kGraphFrames = 200;
constexpr std::array<int, 5> kTimeSpeeds = {1, 10, 60, 600, 3600};
constexpr float kMaxTimeS = 1e6f;  // Scene::time_s's range
// --soak: RSS growth from frame 100 to the end that counts as a leak.
constexpr double kSoakMaxGrowthMiB = 8.0;
constexpr long kSoakFirstFrame = 100;

double now_s() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

// Resident set size (MiB) from /proc/self/statm; 0 where there is none.
double rss_mib() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0.0;
  return double(pages_resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// "2026-06-21T18:30:00Z" for a Julian day (UT): days from the civil calendar's epoch
// (H. Hinnant's civil_from_days).
std::string iso_from_julian_day(double jd) {
  const double unix_s = (jd - 2440587.5) * 86400.0;
  if (!std::isfinite(unix_s) || std::fabs(unix_s) > 1e13) return "?";
  const long long total = (long long)std::floor(unix_s + 0.5);
  long long days = total >= 0 ? total / 86400 : (total - 86399) / 86400;
  const long long second_of_day = total - days * 86400;
  days += 719468;
  const long long era = (days >= 0 ? days : days - 146096) / 146097;
  const long long doe = days - era * 146097;
  const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const long long mp = (5 * doy + 2) / 153;
  const long long day = doy - (153 * mp + 2) / 5 + 1;
  const long long month = mp < 10 ? mp + 3 : mp - 9;
  const long long year = yoe + era * 400 + (month <= 2);
  char text[160];  // room for any long long, so that the compiler sees no truncation
  std::snprintf(text, sizeof text, "%04lld-%02lld-%02lldT%02lld:%02lld:%02lldZ", year, month, day,
                second_of_day / 3600, second_of_day / 60 % 60, second_of_day % 60);
  return text;
}

void glfw_error(int code, const char* message) {
  std::fprintf(stderr, "nephele-view: GLFW error %d: %s\n", code, message);
}

void imgui_vk_check(VkResult result) {
  if (result != VK_SUCCESS)
    std::fprintf(stderr, "nephele-view: ImGui Vulkan backend: VkResult %d\n", int(result));
}

// Owns glfwInit/glfwTerminate and the window.
struct GlfwWindow {
  GLFWwindow* window = nullptr;
  GlfwWindow(int width, int height) {
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit())
      throw RuntimeError("cannot open a window: GLFW failed to start (no display? headless: "
                         "xvfb-run -a nephele-view ...)");
    if (!glfwVulkanSupported()) {
      glfwTerminate();
      throw RuntimeError("cannot open a window: GLFW finds no Vulkan loader");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window = glfwCreateWindow(width, height, "nephele-view", nullptr, nullptr);
    if (!window) {
      glfwTerminate();
      throw RuntimeError("cannot open a window of " + std::to_string(width) + "x" +
                         std::to_string(height));
    }
  }
  ~GlfwWindow() {
    glfwDestroyWindow(window);
    glfwTerminate();
  }
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;
};

class Viewer {
 public:
  explicit Viewer(const ViewerOptions& options);
  ~Viewer();
  int run();

 private:
  void init_imgui();
  bool ensure_swapchain();
  void run_script_commands();
  bool take_screenshot(const std::string& path);
  bool write_window_capture(const std::string& path);
  void handle_input(float dt_s);
  void advance_clock(float dt_s);
  void draw_ui();
  void draw_view_panel();
  void draw_path_panel();
  // Camera paths (path_control.h): flying one, recording the flown camera, writing a path.
  void play_path(CameraPath path, const std::string& name);
  void follow_path();
  void start_recording();
  std::string stop_recording(const std::string& file);
  std::string save_path(const std::string& file, const std::string& parameter);
  void print_camera() const;
  void set_message(const std::string& message, bool is_error);
  void draw_overlay();
  Scene render_scene() const;
  // The display's EV100 for the next frame: with output.auto_exposure, the meter's reading of
  // the last completed frame (FrameStats::metered_luminance), adapted from the EV100 shown
  // before at output.adaptation_ev_per_s over the wall-clock time between frames.
  double display_ev100(const OutputParams& output);
  std::optional<double> display_ev_;  // the auto exposure shown, once a frame was metered
  float applied_ev100_ = 0.0f;        // the exposure the last frame was recorded with
  bool last_reused_ = false;          // the last frame drawn was the one before, settled
  long reused_frames_ = 0;            // frames drawn that way
  std::chrono::steady_clock::time_point display_time_;
  bool draw_frame(const std::string& window_capture_path);

  ViewerOptions options_;
  GlfwWindow glfw_;
  VulkanWindow vk_;
  std::unique_ptr<FrameRenderer> renderer_;
  VkDescriptorPool imgui_pool_ = VK_NULL_HANDLE;
  bool imgui_ready_ = false;

  SceneEditor editor_;
  CameraControl camera_;
  CameraParams applied_camera_;  // what camera_ (or a flight) last wrote into the scene
  PathPlayback flight_;
  PathRecorder recorder_;
  DynamicResolution dynres_;
  bool follow_window_ = true;

  long frame_ = 0;         // frames drawn to the window
  long records_ = 0;       // record_frame calls (frames and screenshots): slot = records_ % 2
  size_t script_next_ = 0;
  bool quit_ = false;
  bool swapchain_stale_ = true;
  int swapchain_for_width_ = -1, swapchain_for_height_ = -1;  // the framebuffer's size then
  int exit_status_ = 0;

  bool playing_ = false;
  int time_speed_ = 1;
  bool show_panel_ = true;
  long last_revision_ = -1;
  bool input_this_frame_ = false;

  double last_frame_s_ = 0.0;
  std::array<float, kGraphFrames> frame_ms_{};
  int graph_next_ = 0;
  double total_frame_ms_ = 0.0;
  long timed_frames_ = 0;
  double soak_start_mib_ = -1.0;

  // Panel inputs.
  char scene_path_[512] = "scene.toml";
  char screenshot_path_[512] = "screenshot.png";
  char path_file_[512] = "flight.toml";
  float goto_altitude_m_ = 2000.0f;
  std::string file_message_;
  bool file_message_is_error_ = false;
};

Viewer::Viewer(const ViewerOptions& options)
    : options_(options),
      glfw_(options.window_width, options.window_height),
      vk_(glfw_.window, VulkanWindowOptions{options.validation, options.device}),
      editor_(options.scene),
      follow_window_(options.follow_window) {
  RendererOptions renderer_options;
  renderer_options.validation = options.validation;
  // The noise textures are made at the first frame (some seconds on a CPU): said on a terminal.
  if (isatty(STDERR_FILENO))
    renderer_options.progress = [](std::string_view stage, int done, int total) {
      if (stage == "noise")
        std::fprintf(stderr, "\rnephele-view: making the noise textures %d/%d%s", done, total,
                     done == total ? "\n" : "");
    };
  renderer_ = std::make_unique<FrameRenderer>(vk_.host(), renderer_options);
  camera_.sync_from(editor_.scene().camera);
  applied_camera_ = editor_.scene().camera;
  dynres_.set_target_ms(options.target_ms);
  dynres_.set_enabled(options.dynamic_resolution);
  if (!ensure_swapchain())
    throw RuntimeError("the window has no area (" + std::to_string(options.window_width) + "x" +
                       std::to_string(options.window_height) + ")");
  init_imgui();
  if (options.camera_path) {
    std::snprintf(path_file_, sizeof path_file_, "%s", options.camera_path_name.c_str());
    play_path(*options.camera_path, options.camera_path_name);
  }
}

Viewer::~Viewer() {
  vkDeviceWaitIdle(vk_.device());
  if (imgui_ready_) {
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (imgui_pool_) vkDestroyDescriptorPool(vk_.device(), imgui_pool_, nullptr);
  renderer_.reset();  // before the device goes
}

void Viewer::init_imgui() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to wherever it runs
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(glfw_.window, true);

  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = 16;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &size;
  vk_check(vkCreateDescriptorPool(vk_.device(), &pool_info, nullptr, &imgui_pool_),
           "vkCreateDescriptorPool");

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = vk_.instance();
  info.PhysicalDevice = vk_.physical_device();
  info.Device = vk_.device();
  info.QueueFamily = vk_.queue_family();
  info.Queue = vk_.queue();
  info.DescriptorPool = imgui_pool_;
  info.Subpass = 0;
  info.MinImageCount = uint32_t(kFramesInFlight);
  info.ImageCount = std::max(vk_.image_count(), uint32_t(kFramesInFlight));
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = imgui_vk_check;
  ImGui_ImplVulkan_Init(&info, vk_.render_pass());
  vk_.run_once([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  imgui_ready_ = true;
}

bool Viewer::ensure_swapchain() {
  // A resize need not make the swapchain out of date (X11 may scale): compare sizes too.
  int width = 0, height = 0;
  glfwGetFramebufferSize(glfw_.window, &width, &height);
  if (width != swapchain_for_width_ || height != swapchain_for_height_) swapchain_stale_ = true;
  if (!swapchain_stale_ && vk_.has_swapchain()) return true;
  swapchain_for_width_ = width;
  swapchain_for_height_ = height;
  if (!vk_.recreate_swapchain()) return false;  // minimised
  swapchain_stale_ = false;
  if (follow_window_) {
    const VkExtent2D e = vk_.extent();
    editor_.change([&](Scene& s) {
      s.output.width = int(e.width);
      s.output.height = int(e.height);
    });
  }
  return true;
}

double Viewer::display_ev100(const OutputParams& output) {
  const auto now = std::chrono::steady_clock::now();
  const double dt_s = std::chrono::duration<double>(now - display_time_).count();
  display_time_ = now;
  if (!output.auto_exposure) {
    display_ev_.reset();
    return output.ev100;
  }
  const std::optional<FrameStats>& stats = renderer_->completed_stats();
  const double metered = stats ? stats->metered_luminance : 0.0;
  const double ev = live_ev100(output, metered, display_ev_ ? &*display_ev_ : nullptr, dt_s);
  if (metered > 0.0) display_ev_ = ev;
  return ev;
}

Scene Viewer::render_scene() const {
  Scene s = editor_.scene();
  s.output.width = dynres_.scaled(s.output.width);
  s.output.height = dynres_.scaled(s.output.height);
  return s;
}

void Viewer::run_script_commands() {
  if (!options_.script) return;
  const Script& script = *options_.script;
  while (script_next_ < script.commands.size() && script.commands[script_next_].frame <= frame_) {
    const ScriptCommand& c = script.commands[script_next_++];
    const std::string where = script.source + ":" + std::to_string(c.line) + ": ";
    std::string error;
    switch (c.action) {
      case ScriptAction::kSet:
        error = editor_.set(c.key, c.argument);
        break;
      case ScriptAction::kPreset:
      case ScriptAction::kLoad:
        try {
          Scene next = c.action == ScriptAction::kPreset ? load_preset(c.argument)
                                                          : load_scene_file(c.argument);
          if (follow_window_) {  // the render size stays the window's
            next.output.width = editor_.scene().output.width;
            next.output.height = editor_.scene().output.height;
          }
          error = editor_.replace(next, c.argument);
        } catch (const InputError& e) {
          error = e.what();
        }
        break;
      case ScriptAction::kScreenshot:
        if (!take_screenshot(c.argument)) exit_status_ = 1;
        break;
      case ScriptAction::kWindowScreenshot:
        break;  // draw_frame captures this frame
      case ScriptAction::kResize:
        glfwSetWindowSize(glfw_.window, c.width, c.height);
        break;
      case ScriptAction::kCameraPath:
        // A path that cannot be read or is malformed leaves the camera (and a flight) as it was.
        try {
          play_path(load_camera_path(c.argument, editor_.scene()), c.argument);
        } catch (const std::exception& e) {
          error = e.what();
        }
        break;
      case ScriptAction::kRecordStart:
        if (recorder_.recording())
          error = "record-start: already recording (record-stop ends a recording)";
        else
          start_recording();
        break;
      case ScriptAction::kRecordStop:
        if (!recorder_.recording()) {
          error = "record-stop: not recording (record-start begins a recording)";
        } else {
          error = stop_recording(c.argument);
          if (!error.empty()) exit_status_ = 1;  // as a screenshot that cannot be written
        }
        break;
      case ScriptAction::kPrintCamera:
        print_camera();
        break;
      case ScriptAction::kQuit:
        quit_ = true;
        return;
    }
    if (!error.empty()) std::fprintf(stderr, "nephele-view: %s%s\n", where.c_str(), error.c_str());
    follow_path();  // a `set time_s` moves a flight's camera before the next command sees it
  }
}

// A still-quality frame of the current scene at its full output size, read back and written:
// what `nephele render` makes of the same scene.
bool Viewer::take_screenshot(const std::string& path) {
  const int slot = int(records_ % kFramesInFlight);
  VkFence fence = vk_.fence(slot);
  vk_check(vkWaitForFences(vk_.device(), 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  VkCommandBuffer cmd = vk_.command_buffer(slot);
  vk_check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  try {
    renderer_->record_frame(cmd, editor_.scene(), FrameOptions{.still = true});
  } catch (const InputError& e) {
    vkEndCommandBuffer(cmd);
    std::fprintf(stderr, "nephele-view: screenshot '%s': %s\n", path.c_str(), e.what());
    return false;
  }
  ++records_;
  vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  vk_check(vkResetFences(vk_.device(), 1, &fence), "vkResetFences");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  vk_check(vkQueueSubmit(vk_.queue(), 1, &submit, fence), "vkQueueSubmit");
  const Frame frame = renderer_->read_back();
  const Scene& scene = editor_.scene();
  const float exposure = still_exposure(scene.output, frame.color);
  try {
    write_image(frame.color, path, exposure, ExrPixels::kHalf, scene.output.tonemap);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "nephele-view: screenshot: %s\n", e.what());
    file_message_ = e.what();
    file_message_is_error_ = true;
    return false;
  }
  file_message_ = "wrote " + path;
  file_message_is_error_ = false;
  std::fprintf(stderr, "nephele-view: wrote %s (%dx%d, still)\n", path.c_str(), frame.color.width,
               frame.color.height);
  return true;
}

void Viewer::handle_input(float dt_s) {
  ImGuiIO& io = ImGui::GetIO();
  CameraInput in;
  float wheel = 0.0f;
  if (!io.WantCaptureKeyboard) {
    const auto key = [&](int k) { return glfwGetKey(glfw_.window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    in.forward = key(GLFW_KEY_W) - key(GLFW_KEY_S);
    in.right = key(GLFW_KEY_D) - key(GLFW_KEY_A);
    in.up = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
    in.roll = key(GLFW_KEY_C) - key(GLFW_KEY_Z);
    if (ImGui::IsKeyPressed(GLFW_KEY_EQUAL) || ImGui::IsKeyPressed(GLFW_KEY_KP_ADD)) wheel += 1.0f;
    if (ImGui::IsKeyPressed(GLFW_KEY_MINUS) || ImGui::IsKeyPressed(GLFW_KEY_KP_SUBTRACT))
      wheel -= 1.0f;
    if (ImGui::IsKeyPressed(GLFW_KEY_F1)) show_panel_ = !show_panel_;
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE)) playing_ = !playing_;
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) {
      if (recorder_.recording()) {
        const std::string error = stop_recording("");
        if (!error.empty()) set_message(error, true);
      } else {
        start_recording();
      }
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_P, false)) {
      if (flight_.playing()) {
        flight_.stop();
        set_message("flight stopped", false);
      } else if (flight_.loaded()) {
        play_path(flight_.path(), flight_.name());
      } else {
        set_message("no path to fly: load one in the panel (Camera path) or record one (R)", true);
      }
    }
  }
  if (!io.WantCaptureMouse) {
    if (ImGui::IsMouseDown(ImGuiMouseButton_Right)) {
      in.look_dx_px = io.MouseDelta.x;
      in.look_dy_px = io.MouseDelta.y;
    }
    wheel += io.MouseWheel;
  }
  if (wheel != 0.0f) {
    if (camera_.mode() == CameraMode::kOrbit)
      camera_.set_orbit_distance_m(camera_.orbit_distance_m() * std::pow(0.8f, wheel));
    else
      camera_.scale_speed(wheel);
  }
  // The panel, a script or a preset moved the camera: take its pose (and end a flight).
  const CameraParams& scene_camera = editor_.scene().camera;
  if (!same_view(scene_camera, applied_camera_)) {
    camera_.sync_from(scene_camera);
    if (flight_.playing()) {
      flight_.stop();
      set_message("flight stopped: the camera was moved", false);
    }
  }
  input_this_frame_ = in.any() || wheel != 0.0f;
  if (in.any() && flight_.playing()) {  // the pilot takes over
    flight_.stop();
    set_message("flight stopped: the keys or the mouse took over", false);
  }
  if (input_this_frame_) {
    camera_.update(in, dt_s);
    editor_.change([&](Scene& s) { camera_.apply_to(s.camera); });
  }
  applied_camera_ = editor_.scene().camera;
}

void Viewer::advance_clock(float dt_s) {
  if (!playing_) return;
  const float step = std::clamp(dt_s, 0.0f, 1.0f) * float(time_speed_);
  const float next = editor_.scene().time_s + step;
  if (std::fabs(next) > kMaxTimeS) {
    playing_ = false;  // time_s's range ends here
    return;
  }
  editor_.change([&](Scene& s) { s.time_s = next; });
}

void Viewer::draw_view_panel() {
  const Scene& scene = editor_.scene();
  if (!ImGui::CollapsingHeader("View and time", ImGuiTreeNodeFlags_DefaultOpen)) return;
  int mode = camera_.mode() == CameraMode::kOrbit ? 1 : 0;
  ImGui::RadioButton("fly", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("orbit", &mode, 1);
  camera_.set_mode(mode == 1 ? CameraMode::kOrbit : CameraMode::kFly);
  float speed = camera_.speed_mps();
  if (ImGui::DragFloat("speed (m/s)", &speed, std::max(0.01f, speed * 0.01f), 0.0f, 0.0f, "%.4g"))
    camera_.set_speed_mps(speed);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("WASD fly, Q/E down/up; mouse wheel or +/- scale the speed (x1.25)");
  if (camera_.mode() == CameraMode::kOrbit) {
    float distance = camera_.orbit_distance_m();
    if (ImGui::DragFloat("orbit distance (m)", &distance, distance * 0.01f, 0.0f, 0.0f, "%.5g")) {
      camera_.set_orbit_distance_m(distance);
      editor_.change([&](Scene& s) { camera_.apply_to(s.camera); });
      applied_camera_ = editor_.scene().camera;
    }
  }
  ImGui::Text("roll %.1f deg (Z/C; positive: right wing down)", double(camera_.roll_deg()));
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.0f);
  ImGui::InputFloat("##altitude", &goto_altitude_m_, 0.0f, 0.0f, "%.0f");
  ImGui::SameLine();
  if (ImGui::Button("go to altitude (m)")) {
    camera_.go_to_altitude(goto_altitude_m_, scene.atmosphere.planet_radius_km);
    editor_.change([&](Scene& s) { camera_.apply_to(s.camera); });
    applied_camera_ = editor_.scene().camera;
  }
  const Geodetic where =
      geodetic_from_enu(scene.camera.position_m, scene.location, scene.atmosphere.planet_radius_km);
  ImGui::Text("lat %.5f  lon %.5f  alt %.1f m", where.lat_deg, where.lon_deg, where.altitude_m);
  ImGui::Text("yaw %.1f  pitch %.1f deg", camera_.yaw_deg(), camera_.pitch_deg());
  if (display_ev_)
    ImGui::Text("exposure EV100 %.1f (auto)", *display_ev_);
  else
    ImGui::Text("exposure EV100 %.1f", scene.output.ev100);

  ImGui::Separator();
  if (ImGui::Button(playing_ ? "pause" : "play")) playing_ = !playing_;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.0f);
  const auto speed_label = [](int speed) {
    std::array<char, 16> text{};
    std::snprintf(text.data(), text.size(), "x%d", speed);
    return text;
  };
  if (ImGui::BeginCombo("time speed", speed_label(time_speed_).data())) {
    for (int s : kTimeSpeeds)
      if (ImGui::Selectable(speed_label(s).data(), s == time_speed_)) time_speed_ = s;
    ImGui::EndCombo();
  }
  const std::optional<double> jd = julian_day_from_iso8601(scene.time);
  if (jd)
    ImGui::Text("sky clock %s", iso_from_julian_day(*jd + double(scene.time_s) / 86400.0).c_str());
  else
    ImGui::TextUnformatted("no date and time (set `time` below): no moon");
  ImGui::Text("time_s %.1f s", double(scene.time_s));
  const std::optional<FrameStats>& stats = renderer_->completed_stats();
  if (stats) {
    ImGui::Text("sun  elevation %6.2f  azimuth %6.2f deg", stats->sun.elevation_deg,
                stats->sun.azimuth_deg);
    if (stats->ephemeris)
      ImGui::Text("moon elevation %6.2f  azimuth %6.2f deg, %.0f%% lit",
                  stats->ephemeris->moon.elevation_deg, stats->ephemeris->moon.azimuth_deg,
                  stats->ephemeris->moon_illuminated_fraction * 100.0);
  }
}

void Viewer::set_message(const std::string& message, bool is_error) {
  file_message_ = message;
  file_message_is_error_ = is_error;
}

// Flies `path` from its first key, now; the clock runs (the path is in scene time).
void Viewer::play_path(CameraPath path, const std::string& name) {
  const double duration_s = path.duration_s();
  const size_t keys = path.keys().size();
  flight_.load(std::move(path), name);
  flight_.play(double(editor_.scene().time_s));
  playing_ = true;
  applied_camera_ = editor_.scene().camera;  // the flight owns the camera from here
  follow_path();
  char text[160];
  std::snprintf(text, sizeof text, "%zu keys, %.1f s of scene time", keys, duration_s);
  set_message("flying " + name + ": " + text, false);
}

// A flight's camera for the scene's time_s. Anything else that moved the camera since the
// flight last placed it (a script's or the panel's edit, a preset) ends the flight.
void Viewer::follow_path() {
  if (!flight_.playing()) return;
  if (!same_view(editor_.scene().camera, applied_camera_)) {
    flight_.stop();
    set_message("flight stopped: the camera was moved", false);
    return;
  }
  const std::optional<CameraParams> camera = flight_.camera_at(double(editor_.scene().time_s));
  if (!camera) return;
  const std::string error = editor_.change([&](Scene& s) { s.camera = *camera; });
  if (!error.empty()) {
    flight_.stop();
    set_message("flight stopped: " + error, true);
    std::fprintf(stderr, "nephele-view: flight %s stopped: %s\n", flight_.name().c_str(),
                 error.c_str());
  }
  applied_camera_ = editor_.scene().camera;
  camera_.sync_from(applied_camera_);
  if (!flight_.playing() && error.empty()) set_message("flight over: " + flight_.name(), false);
}

// Records the scene's camera from now; the clock runs (the keys are in scene time).
void Viewer::start_recording() {
  recorder_.start(double(editor_.scene().time_s), editor_.scene().camera);
  playing_ = true;
  set_message("recording the camera (R stops)", false);
}

// Ends the recording; it becomes the path that "play path" flies, and is written to `file`
// unless that is empty. Returns "" or the message of a write that failed.
std::string Viewer::stop_recording(const std::string& file) {
  CameraPath path = recorder_.stop(double(editor_.scene().time_s), editor_.scene().camera);
  char text[160];
  std::snprintf(text, sizeof text, "recorded %zu keys, %.1f s of scene time", path.keys().size(),
                path.duration_s());
  flight_.load(std::move(path), "the recording");
  set_message(text, false);
  return file.empty() ? "" : save_path(file, "record-stop");
}

// Writes the loaded path (the last recording, or a path file) as TOML (camera_path_to_toml).
std::string Viewer::save_path(const std::string& file, const std::string& parameter) {
  if (!flight_.loaded()) return parameter + ": no path yet (record one, or load a path file)";
  try {
    check_output_file(file, parameter);
    write_file_atomically(file, camera_path_to_toml(flight_.path()));
  } catch (const std::exception& e) {
    set_message(e.what(), true);
    return e.what();
  }
  std::fprintf(stderr, "nephele-view: wrote %s (%zu keys, %.1f s)\n", file.c_str(),
               flight_.path().keys().size(), flight_.path().duration_s());
  set_message("wrote " + file, false);
  return "";
}

// The scene's camera on standard output, as the [camera] table of a scene file.
void Viewer::print_camera() const {
  const Scene& scene = editor_.scene();
  std::string text = "# print-camera: frame " + std::to_string(frame_) + ", time_s " +
                     get_scene_value(scene, "time_s") + "\n[camera]\n";
  for (const SceneParameter& p : scene_parameters())
    if (p.key.starts_with("camera."))
      text += p.key.substr(7) + " = " + get_scene_value(scene, p.key) + "\n";
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
}

void Viewer::draw_path_panel() {
  if (!ImGui::CollapsingHeader("Camera path", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const double time_s = double(editor_.scene().time_s);
  if (recorder_.recording()) {
    if (ImGui::Button("stop recording (R)")) {
      const std::string error = stop_recording("");
      if (!error.empty()) set_message(error, true);
    }
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "REC %zu keys, %.1f s",
                       recorder_.key_count(), recorder_.elapsed_s(time_s));
  } else if (ImGui::Button("record path (R)")) {
    start_recording();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("a key every %.1f s of scene time while the camera moves; the clock runs",
                      PathRecorder::kSampleIntervalS);
  ImGui::InputText("path file", path_file_, sizeof path_file_);
  if (ImGui::Button("load path")) {
    try {
      flight_.load(load_camera_path(path_file_, editor_.scene()), path_file_);
      set_message(std::string("loaded ") + path_file_, false);
    } catch (const std::exception& e) {
      set_message(e.what(), true);
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("save path")) save_path(path_file_, "path file");
  ImGui::SameLine();
  if (flight_.playing()) {
    if (ImGui::Button("stop (P)")) {
      flight_.stop();
      set_message("flight stopped", false);
    }
  } else if (ImGui::Button("play path (P)")) {
    if (flight_.loaded())
      play_path(flight_.path(), flight_.name());
    else
      set_message("no path to fly: load one or record one", true);
  }
  if (flight_.loaded()) {
    const CameraPath& path = flight_.path();
    if (flight_.playing())
      ImGui::Text("flying %s: %.1f of %.1f s", flight_.name().c_str(),
                  flight_.path_time_s(time_s) - path.start_s(), path.duration_s());
    else
      ImGui::Text("path %s: %zu keys, %.1f s", flight_.name().c_str(), path.keys().size(),
                  path.duration_s());
  }
}

void Viewer::draw_overlay() {
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - 10.0f,
                                 viewport->WorkPos.y + 10.0f),
                          ImGuiCond_Always, ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.6f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (ImGui::Begin("frame", nullptr, flags)) {
    ImGui::TextUnformatted(renderer_->device_name().c_str());
    const float last_ms = frame_ms_[size_t((graph_next_ + kGraphFrames - 1) % kGraphFrames)];
    const Scene rs = render_scene();
    ImGui::Text("%.1f ms  %.1f fps  %dx%d (%.0f%%)", double(last_ms),
                last_ms > 0.0f ? 1000.0 / double(last_ms) : 0.0, rs.output.width, rs.output.height,
                double(dynres_.scale()) * 100.0);
    ImGui::PlotLines("##frame ms", frame_ms_.data(), kGraphFrames, graph_next_, "frame ms", 0.0f,
                     FLT_MAX, ImVec2(220.0f, 50.0f));
    if (const auto& stats = renderer_->completed_stats()) {
      ImGui::Text("GPU %.1f ms, record %.1f ms", stats->frame_ms, stats->wall_ms);
      for (const PassTiming& pass : stats->passes)
        ImGui::Text("  %-18s %6.2f ms", pass.name.c_str(), pass.ms);
    }
  }
  ImGui::End();
}

void Viewer::draw_ui() {
  draw_overlay();
  if (!show_panel_) return;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 8.0f, viewport->WorkPos.y + 8.0f),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380.0f, std::max(200.0f, viewport->WorkSize.y - 16.0f)),
                           ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("nephele-view (F1 hides)")) {
    ImGui::End();
    return;
  }
  ImGui::PushItemWidth(ImGui::GetFontSize() * 11.0f);
  // Presets, scene files, screenshots.
  if (ImGui::BeginCombo("preset", "load a preset...")) {
    for (const std::string& name : preset_names())
      if (ImGui::Selectable(name.c_str())) {
        Scene next = load_preset(name);
        if (follow_window_) {
          next.output.width = editor_.scene().output.width;
          next.output.height = editor_.scene().output.height;
        }
        const std::string error = editor_.replace(next, "preset " + name);
        file_message_ = error.empty() ? "preset " + name : error;
        file_message_is_error_ = !error.empty();
      }
    ImGui::EndCombo();
  }
  ImGui::InputText("scene file", scene_path_, sizeof scene_path_);
  if (ImGui::Button("load")) {
    try {
      Scene next = load_scene_file(scene_path_);
      if (follow_window_) {
        next.output.width = editor_.scene().output.width;
        next.output.height = editor_.scene().output.height;
      }
      const std::string error = editor_.replace(next, scene_path_);
      file_message_ = error.empty() ? std::string("loaded ") + scene_path_ : error;
      file_message_is_error_ = !error.empty();
    } catch (const InputError& e) {
      file_message_ = e.what();
      file_message_is_error_ = true;
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("save")) {
    try {
      check_output_file(scene_path_, "scene file");
      write_file_atomically(scene_path_, scene_to_toml(editor_.scene()));
      file_message_ = std::string("saved ") + scene_path_;
      file_message_is_error_ = false;
    } catch (const std::exception& e) {
      file_message_ = e.what();
      file_message_is_error_ = true;
    }
  }
  ImGui::InputText("screenshot", screenshot_path_, sizeof screenshot_path_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip(".png (tone-mapped) or .exr (linear HDR)");
  if (ImGui::Button("take screenshot (still quality)")) {
    try {
      check_output_path(screenshot_path_, "screenshot");
      take_screenshot(screenshot_path_);
    } catch (const InputError& e) {
      file_message_ = e.what();
      file_message_is_error_ = true;
    }
  }
  if (!file_message_.empty()) {
    const ImVec4 color = file_message_is_error_ ? ImVec4(1.0f, 0.35f, 0.3f, 1.0f)
                                                : ImVec4(0.6f, 0.9f, 0.6f, 1.0f);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(color, "%s", file_message_.c_str());
    ImGui::PopTextWrapPos();
  }
  if (!editor_.error().empty() && editor_.error_key().empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1.0f), "%s", editor_.error().c_str());
    ImGui::PopTextWrapPos();
  }

  draw_view_panel();
  draw_path_panel();

  if (ImGui::CollapsingHeader("Performance")) {
    bool enabled = dynres_.enabled();
    if (ImGui::Checkbox("dynamic resolution", &enabled)) dynres_.set_enabled(enabled);
    float target = float(dynres_.target_ms());
    if (ImGui::SliderFloat("target frame (ms)", &target, 8.0f, 500.0f, "%.0f"))
      dynres_.set_target_ms(target);
    ImGui::Checkbox("render at the window's size", &follow_window_);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("off: output.width/height below set the full-quality size");
  }

  for (const ParameterGroup& group : parameter_groups()) {
    const ImGuiTreeNodeFlags open = group.title == "Clouds" ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    if (ImGui::CollapsingHeader(group.title.c_str(), open)) draw_parameter_group(group, editor_);
  }
  ImGui::PopItemWidth();
  ImGui::End();
}

// One frame to the window. Returns false when none was drawn (the swapchain is out of date).
bool Viewer::draw_frame(const std::string& window_capture_path) {
  const int slot = int(records_ % kFramesInFlight);
  VkDevice device = vk_.device();
  VkFence fence = vk_.fence(slot);
  vk_check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

  uint32_t image_index = 0;
  VkResult acquired = vkAcquireNextImageKHR(device, vk_.swapchain(), UINT64_MAX,
                                            vk_.image_available(slot), VK_NULL_HANDLE, &image_index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    swapchain_stale_ = true;
    return false;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) vk_check(acquired, "vkAcquireNextImageKHR");

  VkCommandBuffer cmd = vk_.command_buffer(slot);
  vk_check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vk_check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");

  // The sky; the editor only holds valid scenes, but a refusal must not stop the window.
  std::optional<FrameImages> images;
  try {
    Scene scene = render_scene();
    // The live auto exposure, held where it moves by less than 0.02 EV (1.4%, unseen): the
    // meter's reading of a settled view varies that little from frame to frame, and an
    // unchanged scene lets the renderer hand out its settled frame again (reuse_settled).
    const float ev100 = float(display_ev100(scene.output));
    if (!scene.output.auto_exposure || std::abs(ev100 - applied_ev100_) > 0.02f)
      applied_ev100_ = ev100;
    scene.output.ev100 = applied_ev100_;
    scene.output.auto_exposure = false;
    images = renderer_->record_frame(cmd, scene, FrameOptions{.reuse_settled = true});
    last_reused_ = images->reused;
    reused_frames_ += images->reused ? 1 : 0;
    ++records_;
  } catch (const InputError& e) {
    std::fprintf(stderr, "nephele-view: frame not rendered: %s\n", e.what());
  }

  const VkImage target = vk_.image(image_index);
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageMemoryBarrier to_dst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  to_dst.srcAccessMask = 0;  // the acquire semaphore's wait (at the transfer stage) orders it
  to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  to_dst.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  to_dst.image = target;
  to_dst.subresourceRange = range;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &to_dst);
  const VkExtent2D extent = vk_.extent();
  if (images) {
    // The frame scaled to the window. frame.h leaves `display` in GENERAL; a blit reads best
    // from TRANSFER_SRC_OPTIMAL, so it goes there and back to GENERAL for the next frame.
    VkImageMemoryBarrier to_src{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    to_src.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    to_src.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_src.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
    to_src.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_src.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_src.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_src.image = images->display;
    to_src.subresourceRange = range;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &to_src);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(images->width), int32_t(images->height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cmd, images->display, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   vk_.linear_blit() ? VK_FILTER_LINEAR : VK_FILTER_NEAREST);
    VkImageMemoryBarrier to_general = to_src;
    to_general.srcAccessMask = 0;  // the blit only read it
    to_general.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                               VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    to_general.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_general.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &to_general);
  } else {
    const VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    vkCmdClearColorImage(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
  }

  // The panel over it.
  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = vk_.render_pass();
  pass.framebuffer = vk_.framebuffer(image_index);
  pass.renderArea.extent = extent;
  vkCmdBeginRenderPass(cmd, &pass, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);

  // The whole window, read back (--window-screenshot, or a script's window-screenshot).
  VulkanWindow::HostBuffer capture;
  if (!window_capture_path.empty()) {
    capture = vk_.create_host_buffer(VkDeviceSize(extent.width) * extent.height * 4,
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    VkImageMemoryBarrier to_src = to_dst;
    to_src.srcAccessMask = 0;  // the render pass's dependency made its writes available
    to_src.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_src.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    to_src.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &to_src);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, capture.buffer, 1,
                           &copy);
    VkImageMemoryBarrier to_present = to_dst;
    to_present.srcAccessMask = 0;  // reads only
    to_present.dstAccessMask = 0;
    to_present.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_present.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkBufferMemoryBarrier to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = capture.buffer;
    to_host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT | VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &to_host, 1, &to_present);
  }
  vk_check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");

  vk_check(vkResetFences(device, 1, &fence), "vkResetFences");
  const VkSemaphore wait = vk_.image_available(slot);
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const VkSemaphore signal = vk_.render_finished(image_index);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.waitSemaphoreCount = 1;
  submit.pWaitSemaphores = &wait;
  submit.pWaitDstStageMask = &wait_stage;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  submit.signalSemaphoreCount = 1;
  submit.pSignalSemaphores = &signal;
  vk_check(vkQueueSubmit(vk_.queue(), 1, &submit, fence), "vkQueueSubmit");

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &signal;
  present.swapchainCount = 1;
  VkSwapchainKHR swapchain = vk_.swapchain();
  present.pSwapchains = &swapchain;
  present.pImageIndices = &image_index;
  const VkResult presented = vkQueuePresentKHR(vk_.queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR ||
      acquired == VK_SUBOPTIMAL_KHR)
    swapchain_stale_ = true;
  else
    vk_check(presented, "vkQueuePresentKHR");

  if (capture.buffer) {
    vk_check(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    // BGRA or RGBA to RGBA, alpha opaque.
    const bool bgra = vk_.format() == VK_FORMAT_B8G8R8A8_UNORM;
    const auto* src = static_cast<const unsigned char*>(capture.mapped);
    std::vector<unsigned char> rgba(size_t(extent.width) * extent.height * 4);
    for (size_t i = 0; i < rgba.size(); i += 4) {
      rgba[i + 0] = src[i + (bgra ? 2 : 0)];
      rgba[i + 1] = src[i + 1];
      rgba[i + 2] = src[i + (bgra ? 0 : 2)];
      rgba[i + 3] = 255;
    }
    vk_.destroy(capture);
    std::string png;
    const auto append = [](void* context, void* data, int size) {
      static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    try {
      if (!stbi_write_png_to_func(append, &png, int(extent.width), int(extent.height), 4,
                                  rgba.data(), int(extent.width) * 4))
        throw RuntimeError("cannot encode the PNG");
      write_file_atomically(window_capture_path, png);
      std::fprintf(stderr, "nephele-view: wrote %s (%ux%u, the window, EV100 %.2f%s)\n",
                   window_capture_path.c_str(), extent.width, extent.height,
                   display_ev_ ? *display_ev_ : double(editor_.scene().output.ev100),
                   display_ev_ ? " auto" : "");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "nephele-view: window screenshot: %s\n", e.what());
      exit_status_ = 1;
    }
  }
  return true;
}

int Viewer::run() {
  last_frame_s_ = now_s();
  while (!quit_) {
    glfwPollEvents();
    if (glfwWindowShouldClose(glfw_.window)) break;
    if (options_.frames >= 0 && frame_ >= options_.frames) break;
    if (!ensure_swapchain()) {
      glfwWaitEventsTimeout(0.1);  // minimised: nothing to draw
      last_frame_s_ = now_s();
      continue;
    }
    run_script_commands();
    if (quit_) break;

    const double t = now_s();
    const float dt_s = float(t - last_frame_s_);
    last_frame_s_ = t;
    if (frame_ > 0) {
      const float ms = dt_s * 1000.0f;
      frame_ms_[size_t(graph_next_)] = ms;
      graph_next_ = (graph_next_ + 1) % kGraphFrames;
      if (frame_ > 1) {  // the first frames build noise and tables
        total_frame_ms_ += ms;
        ++timed_frames_;
      }
    }

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input(dt_s);
    advance_clock(dt_s);
    follow_path();
    if (recorder_.recording() &&
        !recorder_.sample(double(editor_.scene().time_s), editor_.scene().camera)) {
      const std::string error = stop_recording("");
      set_message(error.empty() ? "recording stopped: " + std::to_string(PathRecorder::kMaxKeys) +
                                      " keys, the most a path holds (save path writes it)"
                                : error,
                  !error.empty());
    }
    draw_ui();
    ImGui::Render();

    const bool still = !input_this_frame_ && !playing_ && editor_.revision() == last_revision_;
    last_revision_ = editor_.revision();
    // A frame handed out again took no rendering: its time says nothing of the render size.
    if (!last_reused_) dynres_.update(t, double(dt_s) * 1000.0, still);

    // A window capture asked for at this frame.
    std::string capture;
    if (options_.frames >= 0 && frame_ == options_.frames - 1) capture = options_.window_screenshot;
    if (options_.script)
      for (const ScriptCommand& c : options_.script->commands)
        if (c.action == ScriptAction::kWindowScreenshot && c.frame == frame_) capture = c.argument;
    if (!draw_frame(capture)) continue;
    ++frame_;
    if (options_.soak && frame_ == kSoakFirstFrame) soak_start_mib_ = rss_mib();
  }
  vkDeviceWaitIdle(vk_.device());

  if (!options_.screenshot.empty() && !take_screenshot(options_.screenshot)) exit_status_ = 1;
  if (timed_frames_ > 0)
    std::fprintf(stderr,
                 "nephele-view: %ld frames on %s, mean %.1f ms a frame after the first two; %ld "
                 "of them the settled frame again (nothing rendered)\n",
                 frame_, renderer_->device_name().c_str(), total_frame_ms_ / double(timed_frames_),
                 reused_frames_);
  if (options_.soak) {
    const double end_mib = rss_mib();
    if (soak_start_mib_ < 0.0) {
      std::fprintf(stderr, "nephele-view: soak: fewer than %ld frames, nothing measured\n",
                   kSoakFirstFrame);
      exit_status_ = 1;
    } else {
      const double growth = end_mib - soak_start_mib_;
      std::fprintf(stderr,
                   "nephele-view: soak: RSS %.1f MiB at frame %ld, %.1f MiB at frame %ld (%+.1f "
                   "MiB, at most %.0f allowed)\n",
                   soak_start_mib_, kSoakFirstFrame, end_mib, frame_, growth, kSoakMaxGrowthMiB);
      if (growth > kSoakMaxGrowthMiB) exit_status_ = 1;
    }
  }
  return exit_status_;
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  int status = 0;
  {
    Viewer viewer(options);
    status = viewer.run();
  }  // its destruction may be reported too (objects left alive)
  const int messages = VulkanWindow::validation_messages();
  if (options.validation && messages > 0) {
    std::fprintf(stderr, "nephele-view: %d Vulkan validation message%s\n", messages,
                 messages == 1 ? "" : "s");
    status = 1;
  }
  return status;
}

}  // namespace nephele::view
