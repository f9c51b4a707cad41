/* An engine-like host of wirerig, in C, through the C API only (wirerig.h): it loads a built rig
 * (.wrig) and a clip (.wclip), and draws the character in its own GLFW window with its own
 * shaders, evaluating every frame straight into its interleaved vertex buffer. Nothing from
 * wirerig's viewer, scenes or offline code is used.
 *
 *   engine_capi RIG.wrig CLIP.wclip [--frames N] [--script KEY@FRAME,...] [--screenshot OUT.png]
 *
 * Keys: 1 plays the clip, 2 and 3 switch to two poses keyed by joint angles (arms raised,
 * a kick), space pauses, Esc quits. --frames stops after N frames; --script presses keys at
 * frames (e.g. 2@10,1@40) for unattended runs; --screenshot saves the last frame. The last line
 * printed sums up what happened (for the ctest under Xvfb). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "wirerig/wirerig.h"

enum { kClip = 1, kArmsUp = 2, kKick = 3 };
#define kStride 6 /* floats per vertex: position, normal */

typedef struct {
  wr_rig* rig;
  wr_clip* clip;
  wr_context* context;
  int mode;
  int paused;
  double clip_time;
  int switches;
} Engine;

static const char* kVertexShader =
    "#version 330 core\n"
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in vec3 normal;\n"
    "uniform mat4 view_projection;\n"
    "out vec3 world_normal;\n"
    "void main() { world_normal = normal; gl_Position = view_projection * vec4(position, 1); }\n";
static const char* kFragmentShader =
    "#version 330 core\n"
    "in vec3 world_normal;\n"
    "out vec4 color;\n"
    "void main() {\n"
    "  vec3 n = normalize(world_normal);\n"
    "  float key = max(dot(n, normalize(vec3(0.4, 0.8, 0.6))), 0.0);\n"
    "  float fill = 0.5 + 0.5 * n.y;\n"
    "  color = vec4(vec3(0.85, 0.62, 0.48) * (0.25 * fill + 0.8 * key), 1);\n"
    "}\n";

static GLuint Compile(GLenum kind, const char* source) {
  GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, NULL);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024];
    glGetShaderInfoLog(shader, sizeof log, NULL, log);
    fprintf(stderr, "engine_capi: shader: %s\n", log);
    exit(1);
  }
  return shader;
}

/* Column-major 4x4: perspective(fov_y, aspect) * look_at(eye, target, +Y). */
static void ViewProjection(const float eye[3], const float target[3], float aspect, float out[16]) {
  float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (int i = 0; i < 3; ++i) f[i] /= fl;
  float s[3] = {f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0}; /* f x up */
  float sl = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; ++i) s[i] /= sl;
  const float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                      s[0] * f[1] - s[1] * f[0]};
  const float view[16] = {s[0],
                          u[0],
                          -f[0],
                          0,
                          s[1],
                          u[1],
                          -f[1],
                          0,
                          s[2],
                          u[2],
                          -f[2],
                          0,
                          -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                          -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                          f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2],
                          1};
  const float near = 0.05f, far = 50.0f, t = 1.0f / tanf(0.35f);
  const float projection[16] = {t / aspect,
                                0,
                                0,
                                0,
                                0,
                                t,
                                0,
                                0,
                                0,
                                0,
                                (far + near) / (near - far),
                                -1,
                                0,
                                0,
                                2 * far * near / (near - far),
                                0};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float sum = 0;
      for (int k = 0; k < 4; ++k) sum += projection[k * 4 + r] * view[c * 4 + k];
      out[c * 4 + r] = sum;
    }
}

static void Pose(Engine* e, int mode) {
  if (mode == e->mode) return;
  e->mode = mode;
  ++e->switches;
  wr_context_reset(e->context);
  if (mode == kClip) return;
  const struct {
    const char* part;
    float x, y, z;
  } arms_up[] = {{"upper_arm_l", 0, -100, 0},
                 {"upper_arm_r", 0, 100, 0},
                 {"forearm_l", 30, 0, 0},
                 {"forearm_r", 30, 0, 0}},
    kick[] = {{"thigh_l", -80, 0, 0},
              {"shin_l", 40, 0, 0},
              {"upper_arm_r", -60, 0, 0},
              {"forearm_r", 70, 0, 0},
              {"spine_2", 10, 0, 0}};
  const int n = mode == kArmsUp ? 4 : 5;
  for (int i = 0; i < n; ++i) {
    const char* name = mode == kArmsUp ? arms_up[i].part : kick[i].part;
    const int32_t part = wr_rig_find_part(e->rig, name);
    if (part < 0) continue; /* a rig without this joint keeps its rest there */
    if (mode == kArmsUp)
      wr_context_set_joint_angles(e->context, (uint32_t)part, arms_up[i].x, arms_up[i].y,
                                  arms_up[i].z);
    else
      wr_context_set_joint_angles(e->context, (uint32_t)part, kick[i].x, kick[i].y, kick[i].z);
  }
}

static void OnKey(GLFWwindow* window, int key, int scancode, int action, int mods) {
  (void)scancode, (void)mods;
  Engine* e = glfwGetWindowUserPointer(window);
  if (action != GLFW_PRESS) return;
  if (key == GLFW_KEY_1) Pose(e, kClip);
  if (key == GLFW_KEY_2) Pose(e, kArmsUp);
  if (key == GLFW_KEY_3) Pose(e, kKick);
  if (key == GLFW_KEY_SPACE) e->paused = !e->paused;
  if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, 1);
}

static int Fail(const char* what) {
  fprintf(stderr, "engine_capi: %s: %s\n", what, wr_last_error());
  return 1;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    fprintf(stderr,
            "usage: %s RIG.wrig CLIP.wclip [--frames N] [--script KEY@FRAME,...] "
            "[--screenshot OUT.png]\n",
            argv[0]);
    return 2;
  }
  long frames = -1;
  const char* script = "";
  const char* screenshot = NULL;
  for (int i = 3; i + 1 < argc; i += 2) {
    if (strcmp(argv[i], "--frames") == 0)
      frames = strtol(argv[i + 1], NULL, 10);
    else if (strcmp(argv[i], "--script") == 0)
      script = argv[i + 1];
    else if (strcmp(argv[i], "--screenshot") == 0)
      screenshot = argv[i + 1];
    else {
      fprintf(stderr, "engine_capi: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  Engine e = {0};
  if (wr_rig_load_file(argv[1], &e.rig) != WR_OK) return Fail("rig");
  if (wr_clip_load_file(argv[2], &e.clip) != WR_OK) return Fail("clip");
  if (wr_context_create(e.rig, &e.context) != WR_OK) return Fail("context");
  if (wr_context_set_clip(e.context, e.clip, 0.0) != WR_OK) return Fail("clip");
  e.mode = kClip;

  if (!glfwInit()) {
    fprintf(stderr, "engine_capi: GLFW cannot start (no display?)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  const int width = 800, height = 600;
  GLFWwindow* window = glfwCreateWindow(width, height, "wirerig through its C API", NULL, NULL);
  if (!window) {
    fprintf(stderr, "engine_capi: cannot open an OpenGL 3.3 window\n");
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSetWindowUserPointer(window, &e);
  glfwSetKeyCallback(window, OnKey);

  /* The engine's own buffers: welded vertices (one per position), the rig's triangles. */
  const uint32_t vertices = wr_rig_vertex_count(e.rig, WR_ORDER_WELDED);
  const uint32_t triangles = wr_rig_triangle_count(e.rig);
  const size_t floats = (size_t)kStride * vertices;
  float* buffer = malloc(sizeof(float) * floats);
  float* rest = malloc(sizeof(float) * floats);
  uint32_t* indices = malloc(sizeof(uint32_t) * 3 * triangles);
  if (wr_rig_welded_triangles(e.rig, indices, 3 * (size_t)triangles) != WR_OK)
    return Fail("triangles");
  wr_context_set_clip(e.context, NULL, 0.0);
  if (wr_context_evaluate(e.context, WR_ORDER_WELDED, rest, kStride, rest + 3, kStride, floats) !=
      WR_OK)
    return Fail("rest frame");
  wr_context_set_clip(e.context, e.clip, 0.0);
  float low[3] = {1e9f, 1e9f, 1e9f}, high[3] = {-1e9f, -1e9f, -1e9f};
  for (uint32_t v = 0; v < vertices; ++v)
    for (int k = 0; k < 3; ++k) {
      low[k] = fminf(low[k], rest[kStride * v + k]);
      high[k] = fmaxf(high[k], rest[kStride * v + k]);
    }
  const float target[3] = {0.5f * (low[0] + high[0]), 0.5f * (low[1] + high[1]),
                           0.5f * (low[2] + high[2])};
  const float size = fmaxf(high[1] - low[1], fmaxf(high[0] - low[0], high[2] - low[2]));
  const float eye[3] = {target[0] + 0.9f * size, target[1] + 0.25f * size, target[2] + 1.6f * size};
  /* The camera follows a character that travels (root motion: the octopus jets away): it keeps
   * its offset from the vertices' mean, eased so that flailing limbs do not shake it. */
  double rest_mean[3] = {0, 0, 0};
  for (uint32_t v = 0; v < vertices; ++v)
    for (int k = 0; k < 3; ++k) rest_mean[k] += rest[kStride * v + k] / vertices;
  float follow[3] = {0, 0, 0};

  GLuint program = glCreateProgram();
  glAttachShader(program, Compile(GL_VERTEX_SHADER, kVertexShader));
  glAttachShader(program, Compile(GL_FRAGMENT_SHADER, kFragmentShader));
  glLinkProgram(program);
  GLuint vao, vbo, ibo;
  glGenVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * floats), NULL, GL_DYNAMIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, kStride * sizeof(float), (void*)0);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, kStride * sizeof(float),
                        (void*)(3 * sizeof(float)));
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  glGenBuffers(1, &ibo);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(sizeof(uint32_t) * 3 * triangles), indices,
               GL_STATIC_DRAW);
  glEnable(GL_DEPTH_TEST);

  long frame = 0;
  double largest_motion = 0.0;
  int failures = 0;
  while (!glfwWindowShouldClose(window) && (frames < 0 || frame < frames)) {
    /* Scripted key presses due at this frame. */
    for (const char* s = script; *s;) {
      const int key = atoi(s);
      const char* at = strchr(s, '@');
      if (!at) break;
      if (atol(at + 1) == frame)
        OnKey(window, key == 0 ? GLFW_KEY_SPACE : GLFW_KEY_0 + key, 0, GLFW_PRESS, 0);
      const char* next = strchr(at, ',');
      s = next ? next + 1 : at + strlen(at);
    }
    if (e.mode == kClip) {
      if (!e.paused) e.clip_time += 1.0 / 30.0; /* fixed step: runs are reproducible */
      wr_context_set_clip(e.context, e.clip, e.clip_time);
    }
    if (wr_context_evaluate(e.context, WR_ORDER_WELDED, buffer, kStride, buffer + 3, kStride,
                            floats) != WR_OK) {
      ++failures;
      fprintf(stderr, "engine_capi: evaluate: %s\n", wr_last_error());
    }
    for (uint32_t v = 0; v < vertices; ++v) {
      const float* a = buffer + kStride * v;
      const float* b = rest + kStride * v;
      const double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
      if (d > largest_motion) largest_motion = d;
    }
    double mean[3] = {0, 0, 0};
    for (uint32_t v = 0; v < vertices; ++v)
      for (int k = 0; k < 3; ++k) mean[k] += buffer[kStride * v + k] / vertices;
    float eye_now[3], target_now[3];
    for (int k = 0; k < 3; ++k) {
      follow[k] += 0.15f * ((float)(mean[k] - rest_mean[k]) - follow[k]);
      eye_now[k] = eye[k] + follow[k];
      target_now[k] = target[k] + follow[k];
    }
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)(sizeof(float) * floats), buffer);
    int w, h;
    glfwGetFramebufferSize(window, &w, &h);
    glViewport(0, 0, w, h);
    glClearColor(0.78f, 0.84f, 0.9f, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    float view_projection[16];
    ViewProjection(eye_now, target_now, (float)w / (float)(h > 0 ? h : 1), view_projection);
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE,
                       view_projection);
    glDrawElements(GL_TRIANGLES, (GLsizei)(3 * triangles), GL_UNSIGNED_INT, 0);
    ++frame;
    if (screenshot && frames >= 0 && frame == frames) {
      unsigned char* pixels = malloc((size_t)w * (size_t)h * 3);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, pixels);
      stbi_flip_vertically_on_write(1);
      if (!stbi_write_png(screenshot, w, h, 3, pixels, w * 3)) ++failures;
      free(pixels);
    }
    glfwSwapBuffers(window);
    glfwPollEvents();
  }
  printf("engine: frames=%ld switches=%d largest_motion=%.3f m failures=%d\n", frame, e.switches,
         largest_motion, failures);
  free(buffer);
  free(rest);
  free(indices);
  wr_context_free(e.context);
  wr_clip_free(e.clip);
  wr_rig_free(e.rig);
  glfwDestroyWindow(window);
  glfwTerminate();
  return failures == 0 ? 0 : 1;
}
