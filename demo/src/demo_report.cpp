// What the demo tells its user: the CSV log (--log), the status line and the JSON summary
// (--json) (demo_report.hpp).
#include "hapticctrl/demo/demo_report.hpp"

namespace hapticctrl::demo {

void write_log_header(std::ostream& log) {
  log << "t_s,cycle,state_word,x,y,z,qx,qy,qz,qw,vx,vy,vz,contact_fx,contact_fy,contact_fz,"
         "cpl_fx,cpl_fy,cpl_fz,cpl_tx,cpl_ty,cpl_tz,app_fx,app_fy,app_fz,app_tx,app_ty,app_tz,"
         "handle_x,handle_y,handle_z\n";
}

void write_log_row(std::ostream& log, double t, const client::StateSnapshot& s,
                   const SphereScene& scene, const AppliedWrench& applied) {
  log << t << ',' << s.cycle << ',' << s.state_word;
  for (const double v : scene.pose()) {
    log << ',' << v;
  }
  const auto& st = scene.state();
  const Eigen::Vector3d contact = scene.contact_force();
  log << ',' << st.velocity.x() << ',' << st.velocity.y() << ',' << st.velocity.z() << ','
      << contact.x() << ',' << contact.y() << ',' << contact.z();
  for (const double v : s.coupling_wrench) {
    log << ',' << v;
  }
  for (const double v : applied.wrench) {
    log << ',' << v;
  }
  log << ',' << s.handle_pose[0] << ',' << s.handle_pose[1] << ',' << s.handle_pose[2] << '\n';
}

void print_status(FILE* out, double t, const client::StateSnapshot& s, const SphereScene& scene,
                  const char* end) {
  const auto& p = scene.state().position;
  const Eigen::Vector3d contact = scene.contact_force();
  std::fprintf(out,
               "t %6.2f s  %s  sphere (%+.4f %+.4f %+.4f) m  contact %+6.2f %+6.2f %+6.2f N  "
               "coupling %+6.2f %+6.2f %+6.2f N%s",
               t, s.powered() ? "powered  " : "unpowered", p.x(), p.y(), p.z(), contact.x(),
               contact.y(), contact.z(), s.coupling_wrench[0], s.coupling_wrench[1],
               s.coupling_wrench[2], end);
  std::fflush(out);
}

void print_summary_json(FILE* out, const client::StateSnapshot& s, const SphereScene& scene,
                        const client::LinkStatistics& st, std::uint64_t steps,
                        std::uint64_t reconnects, const char* ended) {
  const auto& p = scene.state().position;
  const auto& v = scene.state().velocity;
  const Eigen::Vector3d contact = scene.contact_force();
  std::fprintf(
      out,
      "{\"steps\":%llu,\"reconnects\":%llu,\"ended\":\"%s\",\"powered\":%s,\"sphere_position\":[%."
      "9g,%.9g,%.9g],"
      "\"sphere_velocity\":[%.9g,%.9g,%.9g],\"contact_force\":[%.9g,%.9g,%.9g],"
      "\"penetration\":%.9g,\"coupling_wrench\":[%.9g,%.9g,%.9g,%.9g,%.9g,%.9g],"
      "\"handle_position\":[%.9g,%.9g,%.9g],\"fixed_center\":[%.9g,%.9g,%.9g],"
      "\"answers_received\":%llu,\"answers_lost\":%llu,\"answers_late\":%llu,"
      "\"frames_invalid\":%llu,\"control_sent\":%llu,\"rtt_mean_us\":%.1f,"
      "\"contacts_in_force\":%u,\"contacts_rejected\":%u,\"channel_energy_in\":%.6f,"
      "\"channel_energy_out\":%.6f,\"controller_energy_in\":%.6f}\n",
      static_cast<unsigned long long>(steps), static_cast<unsigned long long>(reconnects), ended,
      s.powered() ? "true" : "false", p.x(), p.y(), p.z(), v.x(), v.y(), v.z(), contact.x(),
      contact.y(), contact.z(), scene.penetration(), s.coupling_wrench[0], s.coupling_wrench[1],
      s.coupling_wrench[2], s.coupling_wrench[3], s.coupling_wrench[4], s.coupling_wrench[5],
      s.handle_pose[0], s.handle_pose[1], s.handle_pose[2], scene.config().fixed_center.x(),
      scene.config().fixed_center.y(), scene.config().fixed_center.z(),
      static_cast<unsigned long long>(st.answers_received),
      static_cast<unsigned long long>(st.answers_lost),
      static_cast<unsigned long long>(st.answers_late),
      static_cast<unsigned long long>(st.frames_invalid),
      static_cast<unsigned long long>(st.control_sent), st.rtt_mean_us, st.contacts_in_force,
      st.contacts_rejected, st.channel_energy_in, st.channel_energy_out, st.controller_energy_in);
}

}  // namespace hapticctrl::demo
