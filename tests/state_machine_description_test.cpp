// SPDX-License-Identifier: MIT
// A description's "state_machine" (bake/RIG_DESCRIPTION.md): one that is
// consistent bakes into the rig and reads back as written; each
// inconsistency fails the bake with one line naming the file, the layer,
// state, transition or input, and the problem, and writes nothing.
#include <string>

#include <nlohmann/json.hpp>

#include "bad_input_support.h"
#include "posemorph/bake/bake.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"

using namespace posemorph;
using namespace posemorph::test;

namespace {

// ValidDescription with two paths and a machine using every kind of state,
// input and condition.
json WithMachine() {
  json j = ValidDescription();
  j["paths"] = json::parse(R"([{"name": "walk", "keys": [[0, 0, 0], [1, 1, 0]]},
                               {"name": "run", "loop": true, "keys": [[0, 0, 0], [0.5, 1, 0], [1, 0, 0]]}])");
  j["state_machine"] = json::parse(R"({
    "inputs": [{"name": "go", "type": "trigger"}, {"name": "speed", "type": "number", "default": 0.5},
               {"name": "held", "type": "bool", "default": true}, {"name": "aim", "type": "point", "default": [0.2, 0]}],
    "layers": [{"initial": "rest",
      "behaviours": {"blink": {"pose": "b", "interval": 2, "seed": 9}, "breath": {"period": 2, "offset": [0, 0.1]},
                     "look_at": {"target": "aim", "strength": 0.5}, "spring": {"frequency": 3}},
      "states": [
        {"name": "rest", "stop": true}, {"name": "walking", "play": "walk", "loop": false, "speed": 2},
        {"name": "pace", "blend": "run", "by": "speed"}, {"name": "aiming", "pad": "aim"}],
      "transitions": [
        {"from": "rest", "to": "walking", "when": ["go"], "mix": 0.1},
        {"from": "walking", "to": "rest", "exit_time": 0.9},
        {"from": "*", "to": "pace", "when": [["speed", ">=", 0.7], ["held", "==", true]], "mix": 0.3},
        {"from": "pace", "to": "aiming", "when": ["!held"]},
        {"from": "aiming", "to": "rest", "when": [["speed", "<", 0.1]], "mix": 0}]}]})");
  return j;
}

}  // namespace

TEST_CASE("a state machine bakes into the rig as the description says") {
  bake::RigDescription d = bake::ParseRigDescription(WithMachine().dump(), "rig.json", ".");
  const std::vector<unsigned char> bytes = bake::BakeRig(d);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  REQUIRE(rig.machine_inputs().size == 4);
  CHECK(rig.format_minor() == format::kVersionMinor);
  CHECK(rig.machine_inputs()[1].type == MachineInputType::kNumber);
  CHECK(rig.machine_inputs()[1].default_x == 0.5);
  CHECK(rig.machine_inputs()[2].default_x == 1);
  CHECK(rig.machine_inputs()[3].default_x == 0.2);
  REQUIRE(rig.machine_layers().size == 1);
  const MachineLayerView& layer = rig.machine_layers()[0];
  CHECK(layer.channel == 0);
  CHECK(layer.state_count == 4);
  CHECK(layer.initial == std::uint32_t(rig.FindMachineState("rest")));
  REQUIRE(layer.any.size == 1);
  CHECK(layer.any[0].to == std::uint32_t(rig.FindMachineState("pace")));
  REQUIRE(layer.any[0].conditions.size == 2);
  CHECK(layer.any[0].conditions[0].op == MachineOp::kGreaterEqual);
  CHECK(layer.any[0].conditions[0].value == 0.7);
  CHECK(layer.any[0].conditions[1].op == MachineOp::kIsTrue);
  CHECK(layer.any[0].mix == 0.3);
  const MachineStateView& walking = rig.machine_states()[rig.FindMachineState("walking")];
  CHECK(walking.kind == MachineStateKind::kPlay);
  CHECK(walking.loop == 0);
  CHECK(walking.speed == 2);
  REQUIRE(walking.transitions.size == 1);
  CHECK(walking.transitions[0].has_exit_time);
  CHECK(walking.transitions[0].exit_time == 0.9);
  CHECK(walking.transitions[0].mix == 0.2);  // the default
  const MachineStateView& pace = rig.machine_states()[rig.FindMachineState("pace")];
  CHECK(pace.kind == MachineStateKind::kBlend);
  CHECK(pace.path == 1);
  CHECK(pace.input == 1);
  REQUIRE(pace.transitions.size == 1);
  CHECK(pace.transitions[0].conditions[0].op == MachineOp::kIsFalse);
  CHECK(rig.machine_states()[rig.FindMachineState("aiming")].kind == MachineStateKind::kPad);
  CHECK(rig.FindMachineState("flying") == -1);
  const MachineBehavioursView& b = layer.behaviours;
  CHECK(b.blink);
  CHECK(b.blink_pose == 1);
  CHECK(b.blink_interval == 2);
  CHECK(b.blink_seed == 9);
  CHECK(b.blink_duration == 0.15);  // the default
  CHECK(b.breath);
  CHECK(b.breath_y == 0.1);
  CHECK(b.look_at);
  CHECK(b.look_input == 3);
  CHECK(b.look_strength == 0.5);
  CHECK(b.spring);
  CHECK(b.spring_frequency == 3);
}

TEST_CASE("a state's colour, opacity and parts bake into the rig (format 1.10)") {
  json j = WithMachine();
  j["state_machine"]["layers"][0]["states"][1]["colour"] = {0.5, 0.75, 1};
  j["state_machine"]["layers"][0]["states"][1]["opacity"] = 0.5;
  j["state_machine"]["layers"][0]["states"][2]["colour"] = {1, 1, 1, 0.25};
  bake::RigDescription d = bake::ParseRigDescription(j.dump(), "rig.json", ".");
  const std::vector<unsigned char> bytes = bake::BakeRig(d);
  Rig rig;
  Error err;
  REQUIRE_MESSAGE(LoadRig(bytes.data(), bytes.size(), &rig, &err), err.message);
  const float walking[4] = {0.5f, 0.75f, 1.0f, 0.5f}, pace[4] = {1, 1, 1, 0.25f}, rest[4] = {1, 1, 1, 1};
  for (int c = 0; c < 4; ++c) {
    CHECK(rig.machine_states()[1].colour[c] == walking[c]);
    CHECK(rig.machine_states()[2].colour[c] == pace[c]);
    CHECK(rig.machine_states()[0].colour[c] == rest[c]);
  }
  // Unchanged without colours: the same bytes as before but for these entries.
  bake::RigDescription plain = bake::ParseRigDescription(WithMachine().dump(), "rig.json", ".");
  CHECK(bake::BakeRig(plain).size() + 2 * 40 == bytes.size());
}

TEST_CASE("posemorph-bake info lists the machine: inputs, layers, behaviours, states, transitions") {
  TempDir dir;
  const fs::path input = dir.path / "rig.json", rig = dir.path / "rig.pmrig";
  Write(input, WithMachine().dump());
  REQUIRE(Run({input.string(), "-o", rig.string()}).status == 0);
  const Result r = Run({"info", rig.string()});
  CAPTURE(r.out);
  REQUIRE(r.status == 0);
  for (const char* line :
       {"MACH ",
        "state machine: 4 inputs: trigger 'go', number 'speed' = 0.5, bool 'held' = true, point 'aim' = (0.2, 0)",
        "layer 0 (channel 0), starts in 'rest'",
        "behaviour: blink toward 'b' every 2 s (jitter 0.5), 0.15 s, strength 1, seed 9 + the character's index",
        "behaviour: look-at point input 'aim', smoothing 0.1 s, strength 0.5",
        "from any state -> 'pace' when speed >= 0.7 and held, mix 0.3 s",
        "state 'walking': plays 'walk' once at speed 2", "-> 'rest' at exit time 0.9, mix 0.2 s",
        "state 'pace': along 'run' by number input 'speed' (0..1)", "-> 'aiming' when not held",
        "state 'aiming': follows point input 'aim'"}) {
    CAPTURE(line);
    CHECK(r.out.find(line) != std::string::npos);
  }
}

TEST_CASE("an inconsistent state machine fails the bake, naming the state, transition or input") {
  auto expect = [](const std::function<void(json&)>& change, const std::string& problem) {
    json j = WithMachine();
    change(j["state_machine"]);
    ExpectFailure(j.dump(), problem);
  };
  auto layer = [](json& m) -> json& { return m["layers"][0]; };
  expect([&](json& m) { layer(m)["transitions"][0]["to"] = "running"; },
         "state_machine.layers[0].transitions[0].to: unknown state \"running\" in this layer");
  expect([&](json& m) { layer(m)["transitions"][0].erase("to"); },
         "state_machine.layers[0].transitions[0]: a transition to nowhere: missing \"to\"");
  expect([&](json& m) { layer(m)["transitions"][0]["when"] = json::array({"jump"}); },
         "state_machine.layers[0].transitions[0].when[0]: unknown input \"jump\"");
  expect([&](json& m) { layer(m)["transitions"][0]["when"] = json::array({"speed"}); },
         "state_machine.layers[0].transitions[0].when[0]: input \"speed\" is a number: compare it");
  expect([&](json& m) { layer(m)["transitions"][0]["when"] = json::parse(R"([["go", ">", 1]])"); },
         "state_machine.layers[0].transitions[0].when[0]: input \"go\" is a trigger and cannot be compared");
  expect([&](json& m) { layer(m)["transitions"][0]["when"] = json::parse(R"([["speed", "=>", 1]])"); },
         "operator \"=>\": expected ==, !=, <, <=, > or >=");
  expect([&](json& m) { layer(m)["transitions"][0].erase("when"); },
         "state_machine.layers[0].transitions[0]: no \"when\" and no \"exit_time\": the transition would fire at "
         "every step");
  expect([&](json& m) { layer(m)["transitions"][3]["exit_time"] = 0.5; },
         "state_machine.layers[0].transitions[3].exit_time: only a transition from a state that plays a path has an "
         "exit time");
  expect([&](json& m) { layer(m)["transitions"][1]["exit_time"] = 1.5; },
         "state_machine.layers[0].transitions[1].exit_time: outside 0..1");
  expect([&](json& m) { layer(m)["transitions"].erase(3); },
         "state_machine.layers[0].states[3]: state \"aiming\" is unreachable: no transition leads to it from \"rest\"");
  expect([&](json& m) { layer(m)["states"][1]["play"] = "swim"; },
         "state_machine.layers[0].states[1].play: unknown path \"swim\"");
  expect([&](json& m) { layer(m)["states"][2]["by"] = "aim"; },
         "state_machine.layers[0].states[2].by: input \"aim\" is a point: a blend moves along its path by a number "
         "input");
  expect([&](json& m) { layer(m)["states"][3]["pad"] = "speed"; },
         "state_machine.layers[0].states[3].pad: input \"speed\" is a number: a pad follows a point input");
  expect([&](json& m) { layer(m)["states"][3]["play"] = "walk"; },
         "state_machine.layers[0].states[3]: state \"aiming\": give exactly one of");
  expect([&](json& m) { layer(m)["states"][3]["name"] = "rest"; },
         "state_machine.layers[0].states[3]: state \"rest\" is declared twice");
  expect([&](json& m) { layer(m)["initial"] = "sleep"; },
         "state_machine.layers[0].initial: unknown state \"sleep\" in this layer");
  expect([&](json& m) { layer(m)["channel"] = "face"; }, "state_machine.layers[0].channel: unknown channel \"face\"");
  expect([&](json& m) { m["inputs"][1]["type"] = "float"; },
         "state_machine.inputs[1].type: \"float\": expected \"bool\", \"number\", \"trigger\" or \"point\"");
  expect([&](json& m) { m["inputs"][3]["name"] = "go"; }, "state_machine.inputs[3]: input \"go\" is declared twice");
  expect([&](json& m) { m["inputs"][0]["default"] = true; },
         "state_machine.inputs[0].default: a trigger has no default");
  expect([&](json& m) { m["layers"].push_back(m["layers"][0]); }, "state_machine.layers: give 1 to 1 layers");
  expect([&](json& m) { layer(m)["behaviours"]["blink"]["pose"] = "z"; },
         "state_machine.layers[0].behaviours.blink.pose: unknown pose \"z\" in the layer's channel");
  expect([&](json& m) { layer(m)["behaviours"]["blink"]["interval"] = 0.001; },
         "state_machine.layers[0].behaviours.blink.interval: outside 0.02..1e+06");
  expect([&](json& m) { layer(m)["behaviours"]["look_at"]["target"] = "held"; },
         "state_machine.layers[0].behaviours.look_at.target: input \"held\" is a bool: look-at follows a point input");
  expect(
      [&](json& m) {
        layer(m)["states"][1]["colour"] = {1, 0.5};
      },
      "state_machine.layers[0].states[1].colour: expected [r, g, b] or [r, g, b, a], each 0..1");
  expect(
      [&](json& m) {
        layer(m)["states"][1]["colour"] = {1, 2, 1};
      },
      "state_machine.layers[0].states[1].colour[1]: outside 0..1");
  expect([&](json& m) { layer(m)["states"][0]["opacity"] = -0.5; },
         "state_machine.layers[0].states[0].opacity: outside 0..1");
  expect(
      [&](json& m) {
        layer(m)["states"][0]["parts"] = {{"arm", 0.5}};
      },
      "state_machine.layers[0].states[0].parts: the character has no parts on its first channel");
  expect([&](json& m) { layer(m)["behaviours"]["wobble"] = json::object(); },
         "state_machine.layers[0].behaviours: unknown behaviour \"wobble\"");
  expect([&](json& m) { layer(m)["behaviours"]["spring"]["frequency"] = 90; },
         "state_machine.layers[0].behaviours.spring.frequency: outside 0.01..20");
  expect(
      [&](json& m) {
        for (int k = 0; k < 65; ++k) m["inputs"].push_back({{"name", "i" + std::to_string(k)}, {"type", "bool"}});
      },
      "state_machine.inputs: 69 inputs, more than the format's 64");
}
