#include "ground_cache.hpp"

#include <deque>
#include <map>
#include <mutex>
#include <system_error>

namespace adjoin::detail {

namespace {

struct Cache {
  std::mutex mutex;
  std::map<std::string, std::shared_ptr<const GroundMotion>> motions;
  std::deque<std::string> order;  // oldest first
};

Cache& cache() {
  static Cache c;
  return c;
}

}  // namespace

std::shared_ptr<const GroundMotion> cached_ground(const std::string& key,
                                                  const std::function<std::shared_ptr<const GroundMotion>()>& make) {
  Cache& c = cache();
  {
    std::lock_guard<std::mutex> lock(c.mutex);
    if (auto it = c.motions.find(key); it != c.motions.end()) return it->second;
  }
  std::shared_ptr<const GroundMotion> made = make();
  std::lock_guard<std::mutex> lock(c.mutex);
  auto [it, inserted] = c.motions.emplace(key, made);
  if (inserted) {
    c.order.push_back(key);
    while (c.order.size() > kGroundCacheSize) {
      c.motions.erase(c.order.front());
      c.order.pop_front();
    }
  }
  return it->second;
}

std::string file_stamp(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  std::string stamp = (error ? path : absolute).string();
  const auto size = std::filesystem::file_size(path, error);
  if (!error) stamp += "|" + std::to_string(size);
  const auto time = std::filesystem::last_write_time(path, error);
  if (!error) stamp += "|" + std::to_string(time.time_since_epoch().count());
  return stamp;
}

}  // namespace adjoin::detail
