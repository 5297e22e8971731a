// SPDX-License-Identifier: MIT
// posemorph-view --watch (watch_bake.h): the bake in memory and the thread
// that watches the description and its files.
#include "watch_bake.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <new>
#include <optional>
#include <thread>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/import/layered_character.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/stage.h"
#include "posemorph/bake/texture_atlas.h"

namespace posemorph::viewer {
namespace {

// The window's textures from an atlas packed in memory: every list shows the
// same pages (premultiplied already).
void DrawingsFromPages(const Rig& rig, const bake::PackedAtlas& atlas, Drawings* out) {
  out->width = atlas.pages[0].width, out->height = atlas.pages[0].height;
  out->rgba.clear();
  for (const bake::AtlasPage& page : atlas.pages) out->rgba.push_back(page.rgba);
  out->pages = std::uint32_t(atlas.pages.size());
  out->attachments.assign(rig.attachment_count(), Drawings{});
  for (Drawings& a : out->attachments)
    a.width = out->width, a.height = out->height, a.rgba = out->rgba, a.pages = out->pages;
}

namespace fs = std::filesystem;

// The files a bake read and what they were then: path, size and time of
// the last change (a file that is missing counts as size -1).
struct Stamp {
  std::string path;
  std::uintmax_t size;
  fs::file_time_type time;
  bool operator==(const Stamp& o) const { return path == o.path && size == o.size && time == o.time; }
};
using Fingerprint = std::vector<Stamp>;

Stamp StampOf(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return {path, std::uintmax_t(-1), {}};
  const fs::file_time_type time = fs::last_write_time(path, ec);
  return {path, size, ec ? fs::file_time_type{} : time};
}

// The description and every file it names that a bake reads or records
// (drawings and images of poses and parts, the layered files it imports),
// resolved as the bake does.
std::vector<std::string> InputsOf(const std::string& description, const bake::RigDescription* d) {
  std::vector<std::string> paths{description};
  if (!d) return paths;
  for (const std::string& f : d->import.files) paths.push_back(f);
  const fs::path folder = fs::path(description).parent_path();
  auto add = [&](const bake::PoseDescription& pose) {
    if (!pose.drawing_path.empty()) paths.push_back(pose.drawing_path);
    if (!pose.image.empty()) paths.push_back((folder / pose.image).string());
  };
  for (const bake::PoseDescription& pose : d->poses) add(pose);
  for (const bake::PartDescription& part : d->parts)
    for (const bake::PoseDescription& pose : part.poses) add(pose);
  return paths;
}

Fingerprint FingerprintOf(const std::vector<std::string>& paths) {
  Fingerprint f;
  for (const std::string& p : paths) f.push_back(StampOf(p));
  return f;
}

class DescriptionWatch final : public WatchedBake {
 public:
  explicit DescriptionWatch(std::string description) : description_(std::move(description)) {}
  ~DescriptionWatch() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  // One bake of the description as it is on disk now: the rig, or false
  // with the message; `inputs` gets the files it read, `read` them as they
  // were when it read them. A description that imports layered files (its
  // "import", which init writes) has their drawings written again first
  // (only those that changed).
  bool Bake(std::unique_ptr<BakedRig>* out, std::string* problem, std::vector<std::string>* inputs, Fingerprint* read) {
    *inputs = InputsOf(description_, nullptr);
    *read = FingerprintOf(*inputs);
    try {
      bake::RigDescription d = bake::ReadRigDescription(description_);
      if (!d.import.files.empty()) {
        std::vector<std::string> notes;
        std::string folder = fs::path(description_).parent_path().string();
        bake::import::ImportAgain(d.import.files, d.import.channels, d.import.flatten, folder.empty() ? "." : folder,
                                  &notes);
      }
      *inputs = InputsOf(description_, &d);
      *read = FingerprintOf(*inputs);
      // The rig as posemorph-bake would write it beside the description, so
      // that it records the description's folder as its drawings' folder.
      fs::path rig_file = description_;
      rig_file.replace_extension(".pmrig");
      d.rig_file = rig_file.string();
      bake::BakeReport report;
      std::vector<unsigned char> bytes = bake::BakeRig(d, &report);
      std::string folder = fs::path(description_).parent_path().string();
      if (folder.empty()) folder = ".";
      // Its atlas as posemorph-bake would pack it, in memory: the window
      // draws from the pages (a drawing may name a layer of a layered file,
      // which only the atlas holds as pixels).
      std::optional<bake::PackedAtlas> atlas;
      if (d.atlas.enabled && bake::ReadRigDrawings(bytes).all) {
        atlas = bake::PackAtlas(bytes, d.rig_file, folder, d.atlas, d.file);
        if (atlas->skipped.empty())
          bytes = std::move(atlas->rig);
        else
          atlas.reset();
      }
      auto baked = std::make_unique<BakedRig>();
      Error err;
      if (!LoadRig(bytes.data(), bytes.size(), &baked->rig, &err)) {
        *problem = description_ + ": the baked rig does not load: " + err.message;
        return false;
      }
      if (atlas) {
        DrawingsFromPages(baked->rig, *atlas, &baked->drawings);
      } else if (!LoadDrawings(baked->rig, folder, &baked->drawings, problem)) {
        *problem = description_ + ": " + *problem;
        return false;
      }
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.1f", report.seconds);
      baked->summary = "baked " + description_ + ": " + std::to_string(report.vertices) + " vertices, " +
                       std::to_string(report.triangles) + " triangles, " + std::to_string(report.poses) + " poses, " +
                       std::to_string(report.bytes) + " bytes, " + seconds + " s";
      *out = std::move(baked);
      return true;
    } catch (const bake::BakeError& e) {
      *problem = e.what();
    } catch (const std::bad_alloc&) {
      *problem = description_ + ": out of memory while " + bake::CurrentBakeStage();
    } catch (const std::exception& e) {
      *problem = description_ + ": internal error: " + e.what();
    }
    return false;
  }

  void Start(std::vector<std::string> inputs, Fingerprint read) {
    inputs_ = std::move(inputs);
    baked_ = std::move(read);
    thread_ = std::thread([this] { Loop(); });
  }

  Result Take(std::unique_ptr<BakedRig>* rig, std::string* message) override {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (ready_) {
      *rig = std::move(ready_);
      return Result::kBaked;
    }
    if (!failed_.empty()) {
      *message = std::move(failed_);
      failed_.clear();
      return Result::kFailed;
    }
    return Result::kNone;
  }

  std::string Progress() const override {
    if (!baking_.load()) return "";
    const auto elapsed =
        std::chrono::steady_clock::now().time_since_epoch() - std::chrono::steady_clock::duration(started_.load());
    const char* stage = bake::LatestBakeStage().stage;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f", std::chrono::duration<double>(elapsed).count());
    return "baking " + description_ + ": " + (stage && *stage ? stage : "starting") + ", " + seconds + " s";
  }

 private:
  // Four times a second: when the inputs differ from those of the last bake
  // and have stayed the same for one more look (an editor writing a file is
  // not read half-way), bake again.
  void Loop() {
    Fingerprint seen = baked_;
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (stop_) break;
      lock.unlock();
      const Fingerprint now = FingerprintOf(inputs_);
      const bool settled = now == seen;
      seen = now;
      if (settled && !(now == baked_)) {
        started_.store(std::chrono::steady_clock::now().time_since_epoch().count());
        baking_.store(true);
        std::unique_ptr<BakedRig> rig;
        std::string problem;
        std::vector<std::string> inputs;
        Fingerprint read;
        const bool ok = Bake(&rig, &problem, &inputs, &read);
        baking_.store(false);
        // What the bake read, as it was when it read it: a change while it
        // ran is baked next.
        inputs_ = inputs;
        baked_ = read;
        seen = baked_;
        lock.lock();
        if (ok)
          ready_ = std::move(rig), failed_.clear();
        else
          failed_ = problem;
        continue;
      }
      lock.lock();
    }
  }

  const std::string description_;
  std::vector<std::string> inputs_;  // the watch thread's own
  Fingerprint baked_;                // the inputs as the last bake read them
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::unique_ptr<BakedRig> ready_;  // under mutex_
  std::string failed_;               // under mutex_
  std::atomic<bool> baking_{false};
  std::atomic<std::chrono::steady_clock::rep> started_{0};
  std::thread thread_;
};

}  // namespace

std::unique_ptr<WatchedBake> WatchDescription(const std::string& description, std::unique_ptr<BakedRig>* first,
                                              std::string* problem) {
  auto watch = std::make_unique<DescriptionWatch>(description);
  std::fprintf(stderr, "posemorph-view: baking %s\n", Printable(description, 1000).c_str());
  std::vector<std::string> inputs;
  Fingerprint read;
  if (!watch->Bake(first, problem, &inputs, &read)) return nullptr;
  watch->Start(std::move(inputs), std::move(read));
  return watch;
}

}  // namespace posemorph::viewer
