# Also find the generated message modules (offshore_gnc.msg) in the catkin devel/install space when this
# source folder comes first on sys.path (tests, the mission job).
__path__ = __import__("pkgutil").extend_path(__path__, __name__)

# The co-operative mission's vehicles, each on its own ROS master (thesis chapter 5): the names of their masters,
# namespaces, configs and bags.
VEHICLES = ("usv", "auv")
