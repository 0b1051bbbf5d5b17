#include "rodlab/solvers/learning/policy.hpp"

#include <nlohmann/json.hpp>

#include "rodlab/check.hpp"
#include "rodlab/solvers/learning/mlp_json.hpp"

namespace rodlab::solvers::learning {
namespace {

using Json = nlohmann::ordered_json;

std::vector<double> to_std(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

/// The field `key` of `j`, or an error naming it.
const Json& field(const Json& j, const std::string& path, const char* key) {
  RODLAB_THROW_UNLESS(j.is_object() && j.contains(key), "policy file: {}{} is missing", path, key);
  return j.at(key);
}

template <class T>
T get(const Json& j, const std::string& path, const char* key) {
  const Json& v = field(j, path, key);
  try {
    return v.get<T>();
  } catch (const nlohmann::json::exception&) {
    throw std::invalid_argument("policy file: " + path + key + " has the wrong type (got " +
                                v.dump() + ")");
  }
}

Eigen::VectorXd vector(const Json& j, const std::string& path, const char* key, int size) {
  const auto v = get<std::vector<double>>(j, path, key);
  RODLAB_THROW_UNLESS(static_cast<int>(v.size()) == size,
                      "policy file: {}{} has {} values, expected {}", path, key, v.size(), size);
  return Eigen::Map<const Eigen::VectorXd>(v.data(), size);
}

}  // namespace

std::string to_json(const Policy& p) {
  RODLAB_THROW_UNLESS(p.lower.size() == p.network.output_size() &&
                          p.upper.size() == p.network.output_size(),
                      "policy: {} action limits for a network of {} outputs", p.lower.size(),
                      p.network.output_size());
  Json j;
  j["schema"] = kPolicySchema;
  j["algorithm"] = p.algorithm;
  j["task"] = p.task;
  j["scene"] = p.scene;
  j["scheme"] = p.scheme;
  j["nodes"] = p.nodes;
  j["dt_control"] = p.dt_control;
  j["observation"] = {{"size", p.network.input_size()},
                      {"goal_velocity", p.layout.goal_velocity},
                      {"state_nodes", p.layout.state_nodes},
                      {"length", p.length},
                      {"period", p.period}};
  j["action"] = {{"size", p.network.output_size()},
                 {"lower", to_std(p.lower)},
                 {"upper", to_std(p.upper)}};
  j["training"] = {{"samples", p.training.samples},
                   {"episodes", p.training.episodes},
                   {"seed", p.training.seed},
                   {"wall_time_s", p.training.wall_time_s},
                   {"episode_steps", p.training.episode_steps}};
  j["goal"] = p.goal ? Json::array({(*p.goal)[0], (*p.goal)[1], (*p.goal)[2]}) : Json(nullptr);
  j["network"] = Json::parse(to_json(p.network));
  return j.dump() + "\n";
}

Policy policy_from_json(std::string_view text) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::invalid_argument(std::string("policy file: not JSON (") + e.what() + ")");
  }
  const auto schema = get<std::string>(j, "", "schema");
  RODLAB_THROW_UNLESS(schema == kPolicySchema, "policy file: schema is '{}', expected '{}'",
                      schema, kPolicySchema);
  Policy p;
  p.algorithm = get<std::string>(j, "", "algorithm");
  p.task = get<std::string>(j, "", "task");
  p.scene = get<std::string>(j, "", "scene");
  p.scheme = get<std::string>(j, "", "scheme");
  p.nodes = get<int>(j, "", "nodes");
  p.dt_control = get<double>(j, "", "dt_control");
  const Json& o = field(j, "", "observation");
  p.layout.goal_velocity = get<bool>(o, "observation.", "goal_velocity");
  p.layout.state_nodes = get<int>(o, "observation.", "state_nodes");
  p.length = get<double>(o, "observation.", "length");
  p.period = get<double>(o, "observation.", "period");
  p.network = from_json<double>(field(j, "", "network").dump());
  RODLAB_THROW_UNLESS(get<int>(o, "observation.", "size") == p.network.input_size(),
                      "policy file: observation.size is {}, the network takes {}",
                      get<int>(o, "observation.", "size"), p.network.input_size());
  const Json& a = field(j, "", "action");
  const int m = p.network.output_size();
  RODLAB_THROW_UNLESS(get<int>(a, "action.", "size") == m,
                      "policy file: action.size is {}, the network gives {}",
                      get<int>(a, "action.", "size"), m);
  p.lower = vector(a, "action.", "lower", m);
  p.upper = vector(a, "action.", "upper", m);
  const Json& t = field(j, "", "training");
  p.training.samples = get<long>(t, "training.", "samples");
  p.training.episodes = get<long>(t, "training.", "episodes");
  p.training.seed = get<std::uint64_t>(t, "training.", "seed");
  p.training.wall_time_s = get<double>(t, "training.", "wall_time_s");
  p.training.episode_steps = get<int>(t, "training.", "episode_steps");
  if (!field(j, "", "goal").is_null()) {
    const Eigen::VectorXd g = vector(j, "", "goal", 3);
    p.goal = lie::Vector3(g[0], g[1], g[2]);
  }
  return p;
}

}  // namespace rodlab::solvers::learning
