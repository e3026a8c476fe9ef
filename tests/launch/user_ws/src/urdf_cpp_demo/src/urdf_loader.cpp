// Reads the arm's URDF and logs it (built by colcon; robomodel does not run C++ nodes).
#include <fstream>
#include <iterator>
#include <string>

#include "rclcpp/rclcpp.hpp"

int main(int argc, char ** argv)
{
  rclcpp::init(argc, argv);
  auto node = rclcpp::Node::make_shared("urdf_loader_node");
  std::ifstream file("src/urdf_cpp_demo/urdf/simple_arm.urdf");
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (text.empty()) {
    RCLCPP_ERROR(node->get_logger(), "Failed to load URDF");
    return 1;
  }
  RCLCPP_INFO(node->get_logger(), "URDF Loaded:\n%s", text.c_str());
  rclcpp::shutdown();
  return 0;
}
