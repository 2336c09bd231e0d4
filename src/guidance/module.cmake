# guidance: the metrics tool reads rosbags (ROS) or CSV.
offshore_gnc_tool(tracking_metrics SOURCES src/guidance/tracking_metrics_main.cpp ROS)
