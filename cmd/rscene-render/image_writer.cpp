#include "rscene-render/image_writer.hpp"

#include <pthread.h>

#include <chrono>
#include <csignal>
#include <filesystem>

#include "common/cli.hpp"
#include "render/image.hpp"
#include "render/output_plan.hpp"
#include "render/view_output.hpp"

namespace rscene::render_cli {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Queued images wait within this many bytes (one job always fits): a few
// 640x480 views, or one 4096x4096 one.
constexpr std::size_t kQueueBytes = std::size_t{256} << 20;

std::size_t bytesOf(const render::ViewImages& i) {
  return i.color.rgba.size() + i.segmentation.rgba.size() + i.depth.size() * sizeof(float);
}

}  // namespace

ImageWriter::ImageWriter(unsigned threads, std::string legend) : legend_(std::move(legend)) {
  for (unsigned i = 0; i < std::max(1u, threads); ++i) workers_.emplace_back([this] { work(); });
}

ImageWriter::~ImageWriter() { finish(); }

bool ImageWriter::submit(ImageJob job) {
  std::size_t bytes = bytesOf(job.images);
  std::unique_lock<std::mutex> lock(mutex_);
  room_.wait(lock, [&] { return failed_ || queue_.empty() || queuedBytes_ + bytes <= kQueueBytes; });
  if (failed_) return false;
  queuedBytes_ += bytes;
  queue_.emplace_back(std::move(job), bytes);
  ready_.notify_one();
  return true;
}

bool ImageWriter::finish() {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_ = true;
    ready_.notify_all();
  }
  for (std::thread& t : workers_)
    if (t.joinable()) t.join();
  return !failed_;
}

void ImageWriter::work() {
  // Stop signals go to the drawing thread, which only sets the stop flag:
  // a job here is written whole (an image with its .npy or .json), never
  // cut between its files by a signal that ends the tool.
  sigset_t stop = cli::stopSignals();
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  for (;;) {
    std::pair<ImageJob, std::size_t> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      ready_.wait(lock, [&] { return done_ || failed_ || !queue_.empty(); });
      if (failed_ || queue_.empty()) return;
      job = std::move(queue_.front());
      queue_.pop_front();
      ++busy_;
    }
    bool ok = run(job.first);
    std::unique_lock<std::mutex> lock(mutex_);
    --busy_;
    queuedBytes_ -= job.second;
    if (!ok) failed_ = true;
    room_.notify_all();
    if (failed_) ready_.notify_all();
  }
}

bool ImageWriter::run(const ImageJob& job) {
  const render::ViewImages& im = job.images;
  for (const auto& [path, pass] : job.outputs) {
    auto t = Clock::now();
    std::vector<std::string> files = render::filesOf(path, pass);
    std::vector<std::string> bytes;
    if (pass == render::Pass::Color)
      bytes = {render::encodePng(im.color)};
    else if (pass == render::Pass::Segmentation)
      bytes = {render::encodePng(im.segmentation), legend_};
    else
      bytes = {render::encodeDepthPng16(im.depth, im.width, im.height),
               render::encodeDepthNpy(im.depth, im.width, im.height)};
    double encoded = since(t);
    t = Clock::now();
    for (std::size_t k = 0; k < files.size(); ++k) {
      if (bytes[k].empty()) {
        cli::error(files[k] + ": the renderer gave no " + render::passName(pass) + " image");
        return false;
      }
      std::filesystem::path parent = std::filesystem::path(files[k]).parent_path();
      std::error_code ec;
      if (!parent.empty()) std::filesystem::create_directories(parent, ec);  // writeOutput reports what fails
      if (!cli::writeOutput(files[k], [&](Sink& s) {
            s.write(bytes[k]);
            return true;
          }))
        return false;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    encodeSeconds_ += encoded;
    writeSeconds_ += since(t);
    files_ += files.size();
  }
  return true;
}

}  // namespace rscene::render_cli
