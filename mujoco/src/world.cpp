// Implements world.hpp: the MuJoCo model, its data and the coupled free body.
#include "hapticctrl/mujoco/world.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "world_engine.hpp"

namespace hapticctrl::mujoco {
namespace {

constexpr int kErrorTextSize = 1000;
constexpr double kMaxReportDistance = 1.0;  // m, the protocol's largest gap

/// MuJoCo's own handlers print to stdout (where the --json summary goes) and append to
/// MUJOCO_LOG.TXT in the working directory: these say it on stderr, once per text, and nothing
/// is written to disk.
void warn(const char* text) {
  static std::string last;
  if (last != text) {
    last = text;
    std::fprintf(stderr, "hapticctrl-mujoco: MuJoCo: %s\n", text);
  }
}
[[noreturn]] void fail(const char* text) {
  // A MuJoCo error inside a step leaves its data unusable and MuJoCo expects no return: the
  // program ends; the controller's session watchdog takes the arm to its safe state.
  std::fprintf(stderr, "hapticctrl-mujoco: MuJoCo error: %s\n", text);
  std::_Exit(1);
}

/// The custom text MJCF element naming the coupled body: <custom><text name="hapticctrl_body"
/// data="NAME"/></custom>.
std::string body_named_by(const mjModel* m) {
  const int id = mj_name2id(m, mjOBJ_TEXT, "hapticctrl_body");
  if (id < 0) {
    return {};
  }
  const int length = m->text_size[id];
  return std::string(m->text_data + m->text_adr[id],
                     static_cast<std::size_t>(std::max(0, length - 1)));
}

bool is_free(const mjModel* m, int body) {
  return m->body_jntnum[body] == 1 && m->jnt_type[m->body_jntadr[body]] == mjJNT_FREE;
}

std::string name_of_body(const mjModel* m, int body) {
  const char* name = mj_id2name(m, mjOBJ_BODY, body);
  return name != nullptr ? name : "body " + std::to_string(body);
}

std::string free_body_names(const mjModel* m) {
  std::string names;
  for (int b = 1; b < m->nbody; ++b) {
    if (is_free(m, b)) {
      names += names.empty() ? "" : ", ";
      names += name_of_body(m, b);
    }
  }
  return names.empty() ? "none" : names;
}

/// The adhesion actuators on `body` (a body transmission).
std::vector<int> grips_of(const mjModel* m, int body) {
  std::vector<int> grips;
  for (int a = 0; a < m->nu; ++a) {
    if (m->actuator_trntype[a] == mjTRN_BODY && m->actuator_trnid[at(2, a)] == body) {
      grips.push_back(a);
    }
  }
  return grips;
}

}  // namespace

World::World(const std::string& path, const std::string& body, double timestep)
    : engine_(std::make_unique<Engine>()) {
  mju_user_warning = warn;
  mju_user_error = fail;
  std::array<char, kErrorTextSize> error{};
  Engine& e = *engine_;
  e.model = mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size()));
  if (e.model == nullptr) {
    throw std::invalid_argument("cannot load the model '" + path + "': " + error.data());
  }
  if (timestep > 0.0) {
    e.model->opt.timestep = timestep;
  }
  body_name_ = body.empty() ? body_named_by(e.model) : body;
  if (body_name_.empty()) {
    throw std::invalid_argument("no body to couple: name one with --body (free bodies in '" + path +
                                "': " + free_body_names(e.model) + ")");
  }
  e.body = mj_name2id(e.model, mjOBJ_BODY, body_name_.c_str());
  if (e.body < 0) {
    throw std::invalid_argument("the model has no body '" + body_name_ +
                                "' (free bodies: " + free_body_names(e.model) + ")");
  }
  const int joint = e.model->body_jntadr[e.body];
  if (!is_free(e.model, e.body)) {
    throw std::invalid_argument("the body '" + body_name_ +
                                "' is not free: the hand holds a body with a free joint "
                                "(<freejoint/>) and no other (free bodies: " +
                                free_body_names(e.model) + ")");
  }
  e.qpos = e.model->jnt_qposadr[joint];
  e.dof = e.model->jnt_dofadr[joint];
  const int first = e.model->body_geomadr[e.body];
  for (int g = first; g >= 0 && g < first + e.model->body_geomnum[e.body]; ++g) {
    e.margin.push_back(e.model->geom_margin[g]);
  }
  for (int p = 0; p < e.model->npair; ++p) {
    if (e.model->geom_bodyid[e.model->pair_geom1[p]] == e.body ||
        e.model->geom_bodyid[e.model->pair_geom2[p]] == e.body) {
      e.pair_margins.emplace_back(p, e.model->pair_margin[p]);
    }
  }
  e.grips = grips_of(e.model, e.body);
  e.mesh_boxes = mesh_boxes_of(e.model);
  e.drawn_geoms = drawn_geoms_of(e.model);
  e.data = mj_makeData(e.model);
  e.report_model = mj_copyModel(nullptr, e.model);
  e.report_data = e.report_model != nullptr ? mj_makeData(e.report_model) : nullptr;
  if (e.data == nullptr || e.report_data == nullptr) {
    throw std::runtime_error("MuJoCo could not allocate the model's data");
  }
  mj_forward(e.model, e.data);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

double World::timestep() const noexcept {
  return engine_->model->opt.timestep;
}

double World::time() const noexcept {
  return engine_->data->time;
}

double World::mass() const noexcept {
  return engine_->model->body_mass[engine_->body];
}

std::array<double, 3> World::inertia() const noexcept {
  const double* i = engine_->model->body_inertia + at(3, engine_->body);
  return {i[0], i[1], i[2]};
}

void World::step(const client::Vector6& wrench) noexcept {
  const Engine& e = *engine_;
  const bool finite =
      std::all_of(wrench.begin(), wrench.end(), [](double v) { return std::isfinite(v); });
  // MuJoCo applies xfrc_applied at the centre of mass: the torque of the force about it is added
  // (the wrench acts at the body's origin, which is what the controller is sent).
  mjtNum rotation[9];
  mju_quat2Mat(rotation, e.data->qpos + e.qpos + 3);
  mjtNum to_com[3];
  mju_rotVecMat(to_com, e.model->body_ipos + at(3, e.body), rotation);
  mjtNum* out = e.data->xfrc_applied + at(6, e.body);
  for (int i = 0; i < 6; ++i) {
    out[i] = finite ? wrench[static_cast<std::size_t>(i)] : 0.0;
  }
  mjtNum lever[3];  // (origin - com) x force
  const mjtNum back[3] = {-to_com[0], -to_com[1], -to_com[2]};
  mju_cross(lever, back, out);
  mju_addTo3(out + 3, lever);
  mj_step(e.model, e.data);
}

client::Pose7 World::pose() const noexcept {
  const mjtNum* q = engine_->data->qpos + engine_->qpos;
  return {q[0], q[1], q[2], q[4], q[5], q[6], q[3]};  // MuJoCo's quaternion is w x y z
}

client::Vector6 World::twist() const noexcept {
  const Engine& e = *engine_;
  const mjtNum* v = e.data->qvel + e.dof;
  mjtNum rotation[9];
  mju_quat2Mat(rotation, e.data->qpos + e.qpos + 3);
  mjtNum angular[3];
  mju_rotVecMat(angular, v + 3, rotation);  // body frame -> world
  return {v[0], v[1], v[2], angular[0], angular[1], angular[2]};
}

void World::set_report_distance(double distance) noexcept {
  const Engine& e = *engine_;
  const double d = std::isfinite(distance) ? std::clamp(distance, 0.0, kMaxReportDistance) : 0.0;
  const int first = e.model->body_geomadr[e.body];
  for (std::size_t i = 0; i < e.margin.size(); ++i) {
    e.report_model->geom_margin[first + static_cast<int>(i)] = e.margin[i] + d;
  }
  for (const auto& [pair, margin] : e.pair_margins) {
    e.report_model->pair_margin[pair] = margin + d;
  }
}

std::size_t World::contacts(std::span<EngineContact> out) noexcept {
  const Engine& e = *engine_;
  // The state now, positions only, through the collision pass of the report model.
  mju_copy(e.report_data->qpos, e.data->qpos, e.model->nq);
  mju_copy(e.report_data->mocap_pos, e.data->mocap_pos, 3 * e.model->nmocap);
  mju_copy(e.report_data->mocap_quat, e.data->mocap_quat, 4 * e.model->nmocap);
  mj_kinematics(e.report_model, e.report_data);
  mj_collision(e.report_model, e.report_data);
  const mjModel* m = e.report_model;
  std::size_t count = 0;
  for (int i = 0; i < e.report_data->ncon; ++i) {
    const mjContact& c = e.report_data->contact[i];
    const bool first = m->geom_bodyid[c.geom1] == e.body;
    const bool second = m->geom_bodyid[c.geom2] == e.body;
    // Fused, equality or motionless pairs (exclude > 1) are not contacts.
    if ((!first && !second) || c.exclude > 1) {
      continue;
    }
    EngineContact found;
    found.distance = c.dist;
    found.body_is_geom2 = second;
    found.condim = c.dim;
    found.pyramidal = m->opt.cone == mjCONE_PYRAMIDAL;
    std::copy_n(c.friction, found.friction.size(), found.friction.begin());
    found.inverse_weight = m->body_invweight0[at(2, m->geom_bodyid[c.geom1])] +
                           m->body_invweight0[at(2, m->geom_bodyid[c.geom2])];
    for (std::size_t k = 0; k < 3; ++k) {
      found.midpoint[k] = c.pos[k];
      found.normal[k] = c.frame[k];
    }
    std::copy_n(c.solref, found.solref.size(), found.solref.begin());
    std::copy_n(c.solimp, found.solimp.size(), found.solimp.begin());
    // Insertion into the deepest-first list, of at most out.size().
    std::size_t at = count;
    while (at > 0 && out[at - 1].distance > found.distance) {
      --at;
    }
    if (at >= out.size()) {
      continue;
    }
    count = std::min(count + 1, out.size());
    for (std::size_t k = count - 1; k > at; --k) {
      out[k] = out[k - 1];
    }
    out[at] = found;
  }
  return count;
}

std::array<double, 3> World::contact_force() const noexcept {
  const Engine& e = *engine_;
  std::array<double, 3> total{};
  for (int i = 0; i < e.data->ncon; ++i) {
    const mjContact& c = e.data->contact[i];
    const bool first = e.model->geom_bodyid[c.geom1] == e.body;
    const bool second = e.model->geom_bodyid[c.geom2] == e.body;
    if ((!first && !second) || c.efc_address < 0) {
      continue;
    }
    mjtNum local[6];
    mj_contactForce(e.model, e.data, i, local);
    // In the contact's frame (rows: normal, two tangents), the force on geom2.
    const double sign = second ? 1.0 : -1.0;
    for (std::size_t k = 0; k < 3; ++k) {
      total[k] +=
          sign * (local[0] * c.frame[k] + local[1] * c.frame[3 + k] + local[2] * c.frame[6 + k]);
    }
  }
  return total;
}

int World::instabilities() const noexcept {
  return engine_->data->warning[mjWARN_BADQACC].number;
}

void World::reset() noexcept {
  const int bad = instabilities();
  mj_resetData(engine_->model, engine_->data);
  engine_->data->warning[mjWARN_BADQACC].number = bad;  // counted over the whole run
  mj_forward(engine_->model, engine_->data);
}

bool World::has_grip() const noexcept {
  return !engine_->grips.empty();
}

void World::set_grip(bool on) noexcept {
  const Engine& e = *engine_;
  for (const int a : e.grips) {
    // An unlimited control range has no top: 1 is then the actuator's gain as written.
    const bool limited = e.model->actuator_ctrllimited[a] != 0;
    e.data->ctrl[a] = on ? (limited ? e.model->actuator_ctrlrange[2 * a + 1] : 1.0) : 0.0;
  }
}

std::vector<std::pair<std::string, std::array<double, 3>>> World::free_bodies() const {
  const Engine& e = *engine_;
  std::vector<std::pair<std::string, std::array<double, 3>>> out;
  for (int b = 1; b < e.model->nbody; ++b) {
    if (b != e.body && is_free(e.model, b)) {
      const mjtNum* q = e.data->qpos + e.model->jnt_qposadr[e.model->body_jntadr[b]];
      out.emplace_back(name_of_body(e.model, b), std::array<double, 3>{q[0], q[1], q[2]});
    }
  }
  return out;
}

std::vector<std::pair<std::string, double>> World::joints() const {
  const Engine& e = *engine_;
  std::vector<std::pair<std::string, double>> out;
  for (int j = 0; j < e.model->njnt; ++j) {
    const char* name = mj_id2name(e.model, mjOBJ_JOINT, j);
    const int type = e.model->jnt_type[j];
    if (name != nullptr && (type == mjJNT_HINGE || type == mjJNT_SLIDE)) {
      out.emplace_back(name, e.data->qpos[e.model->jnt_qposadr[j]]);
    }
  }
  return out;
}

std::string engine_version() {
  return "MuJoCo " + std::string(mj_versionString());
}

}  // namespace hapticctrl::mujoco
