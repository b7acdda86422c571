// Encodes and writes the images of rendered views on worker threads while
// the main thread draws the next view: PNG encoding costs about as much as
// drawing on the CPU backend, so a trajectory of many views would otherwise
// take twice as long.  Memory is bounded: submit() waits while the queued
// images exceed a byte budget.
#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "render/view.hpp"

namespace rscene::render_cli {

struct ImageJob {
  render::ViewImages images;
  std::vector<std::pair<std::string, render::Pass>> outputs;  // image path and pass
};

class ImageWriter {
 public:
  // `legend`: the segmentation legend JSON written beside every
  // segmentation image (the same for every frame).
  ImageWriter(unsigned threads, std::string legend);
  ~ImageWriter();  // finish()es
  // Queues one view's images.  False once a write has failed (the failure
  // is printed by then); nothing more is written after it.
  bool submit(ImageJob job);
  // Waits for every queued job; false if any failed.
  bool finish();
  unsigned threads() const { return static_cast<unsigned>(workers_.size()); }
  std::size_t filesWritten() const { return files_; }
  double encodeSeconds() const { return encodeSeconds_; }  // summed over the threads
  double writeSeconds() const { return writeSeconds_; }

 private:
  void work();
  bool run(const ImageJob& job);

  std::string legend_;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable ready_, room_;
  std::deque<std::pair<ImageJob, std::size_t>> queue_;  // job and its bytes
  std::size_t queuedBytes_ = 0;
  unsigned busy_ = 0;
  bool failed_ = false, done_ = false;
  std::size_t files_ = 0;
  double encodeSeconds_ = 0, writeSeconds_ = 0;
};

}  // namespace rscene::render_cli
