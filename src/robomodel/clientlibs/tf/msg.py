"""tf's message module: ``tf.msg.tfMessage``, the message of ``/tf`` in ROS 1's tf (ROS 1's
``tf/tfMessage`` has the definition, so the md5sum, of ``tf2_msgs/TFMessage``; robomodel
offers it as that type, the genpy-flavoured class)."""

from robomodel.clientlibs.messages import message_class

__all__ = ["tfMessage"]

tfMessage = message_class("tf2_msgs/msg/TFMessage", "genpy")
